"""Study files: what to compute over which cases (TOML: the file formats, study files).

::

    name = "bushing-tolerance"          # optional
    description = "..."                 # optional

    [study]
    kind = "monte-carlo"                # grid | monte-carlo | latin-hypercube | sobol | files
    samples = 10000                     # monte-carlo, latin-hypercube; sobol: base sample N
    seed = 1
    stages = ["risk"]                   # any of derive, fit, risk
    texture = "wedge-asymmetric.toml"   # or a [texture] table; optional when the assembly
    assembly = "bushing-strip.toml"     #   names one (paths relative to the study file)
    # files = ["scans/*.x3p"]           # kind = "files": one case per file
    # unit, pixel_size, height_scale, detrend, mu, max_slope, despike, despike_window:
    #                                   # how to read the files (as derive's flags)
    # contact = "all-faces"             # contact regime (default: the assembly's, else all-faces)
    # directions = 72                   # sliding directions of derive / fit
    # law = "star"                      # fit: star or ellipse
    # cycles, tolerance                 # risk: life and drift tolerance (default: the assembly's)
    # output = "drift_per_cycle_m"      # sobol: the output whose variance is split
    # batch_size = 500                  # cases per task (default: chosen from the case cost)

    [parameters]                        # TABLE.KEY of the texture or assembly file it replaces
    "texture.alpha_deg" = { distribution = "normal", mean = 30.0, sd = 1.5 }
    "loading.dT_max"    = { distribution = "uniform", low = 90.0, high = 140.0 }

:func:`load_study` checks everything it can before any work: the keys, the
distributions, the files named, and one case built from the parameters' medians (a
parameter the texture or assembly does not have, or a median outside its range, is
refused in one line naming the field).
"""
from __future__ import annotations

import copy
import hashlib
import json
import os
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import InputError, check_choice, check_int, check_range, check_text
from .inputs import StudyFiles, assembly_key, read_input_toml, study_files
from .sampling import KINDS, Parameter, case_count, check_sobol_base, parse_parameter

STAGES = ("derive", "fit", "risk", "crawl")
TABLES = ("texture", "assembly", "friction", "loading", "contact", "crawl")
_TOP = {"name", "description", "study", "texture", "parameters", "contact", "crawl"}
_STUDY = {"kind", "samples", "seed", "stages", "texture", "assembly", "files", "unit",
          "pixel_size", "height_scale", "detrend", "mu", "max_slope", "despike",
          "despike_window", "contact", "directions", "law",
          "cycles", "tolerance", "output", "batch_size"}


class StudyFileError(InputError):
    """A study file cannot be read or does not follow the format."""


@dataclass(frozen=True)
class Study:
    """A parsed study: the cases (parameters and their sampling, or files) and the work
    each case does (``spec``: plain data sent to the workers)."""

    name: str
    description: str
    kind: str
    samples: int | None
    seed: int
    parameters: tuple[Parameter, ...]
    files: tuple[str, ...]
    spec: dict                         # the work of one case (see asperity.study.cases)
    batch_size: int | None
    source: str                        # the study file
    text: str = field(default="", repr=False)   # its contents, kept in the store
    inputs: tuple[str, ...] = ()       # every file it names (asperity.study.inputs)

    @property
    def n_cases(self) -> int:
        if self.kind == "files":
            return len(self.files) * self._per_file
        return case_count(self.kind, list(self.parameters), self.samples)

    @property
    def _per_file(self) -> int:
        """Cases of each file of a library: the grid of its contact parameters (or 1)."""
        return case_count("grid", list(self.parameters), None) if self.parameters else 1

    @property
    def case_files(self) -> tuple[str, ...]:
        """The file of every case of a library (each file at every grid point in turn)."""
        return tuple(f for f in self.files for _ in range(self._per_file))

    @property
    def parameter_names(self) -> list[str]:
        return [p.name for p in self.parameters]

    def fingerprint(self) -> str:
        """A hash of everything the study file decides (not the batch size or the file's
        comments); with :meth:`input_digests`, what a store must match to be resumed."""
        data = {"kind": self.kind, "samples": self.samples, "seed": self.seed,
                "parameters": [(p.name, p.distribution, p.args, p.values)
                               for p in self.parameters], "spec": self.spec}
        text = json.dumps(data, sort_keys=True, default=str)
        return hashlib.sha256(text.encode()).hexdigest()

    def input_digests(self) -> dict[str, str]:
        """{path: SHA-256 of its content} of every file the study names (the scans of a
        library, the texture, assembly and gauge files): their content, not their names
        or sizes, decides the results."""
        from .inputs import digests
        return digests(self.inputs)

    def matrix(self):
        """(cases, parameters) values of every case (files: (files, 0))."""
        import numpy as np

        from .sampling import sample_matrix
        if self.kind == "files":
            if not self.parameters:
                return np.zeros((len(self.files), 0))
            grid = sample_matrix("grid", list(self.parameters), None, self.seed)
            return np.tile(grid, (len(self.files), 1))
        return sample_matrix(self.kind, list(self.parameters), self.samples, self.seed)

    def to_dict(self) -> dict:
        return {"name": self.name, "kind": self.kind, "samples": self.samples,
                "seed": self.seed, "cases": self.n_cases, "stages": self.spec["stages"],
                "parameters": {p.name: p.describe() for p in self.parameters},
                "files": len(self.files) if self.kind == "files" else None,
                "source": self.source}


def load_study(path, confine=None) -> Study:
    """Read and check a study file; one-line StudyFileError naming the field.

    ``confine``: an :class:`asperity.study.inputs.Confine` to refuse every file name (of
    the study or its assembly) that resolves outside its folder."""
    from ..io import parse_toml, read_text_file
    if not isinstance(path, (str, os.PathLike)) or not str(path):
        raise StudyFileError(f"a study file must be a path, got {path!r}")
    p = Path(path)
    text = read_text_file(p, "study file", StudyFileError)
    data = parse_toml(text, p, StudyFileError)
    try:
        return study_from_dict(data, p, text, confine)
    except StudyFileError:
        raise
    except InputError as exc:
        raise StudyFileError(f"{p}: {exc}") from None


def study_from_dict(data: dict, path, text: str = "", confine=None) -> Study:
    """A study from the tables of a study file; ``path`` resolves the files it names
    (``confine`` as :func:`load_study`)."""
    p = Path(path)
    folder = p.parent
    unknown = sorted(set(data) - _TOP)
    if unknown:
        raise InputError(f"unknown key {unknown[0]!r}; allowed top-level keys: "
                         f"{', '.join(sorted(_TOP))}")
    st = data.get("study")
    if not isinstance(st, dict):
        raise InputError("missing table [study] (kind, samples, seed, stages, ...)")
    unknown = sorted(set(st) - _STUDY)
    if unknown:
        raise InputError(f"unknown key study.{unknown[0]}; allowed: {', '.join(sorted(_STUDY))}")
    kind = check_choice("study.kind", st.get("kind"), KINDS)
    name = check_text("name", data.get("name", p.stem), 200)
    description = check_text("description", data.get("description", ""), 4096)
    samples = _samples(kind, st)
    seed = check_int("study.seed", st.get("seed", 0), 0, 2**63 - 1)
    batch = None if "batch_size" not in st else check_int("study.batch_size", st["batch_size"],
                                                          1, 1_000_000)
    params = _parameters(data.get("parameters", {}), kind)
    named = study_files(st, folder, kind, confine)
    if kind != "files" and "files" in st:
        raise InputError("study.files belongs to kind = \"files\" (a scan library)")
    files = named.scans if kind == "files" else ()
    spec = _spec(st, data, kind, params, named)
    study = Study(name, description, kind, samples, seed, tuple(params), files, spec, batch,
                  str(p), text, named.existing)
    from .sampling import MAX_CASES
    if kind != "files" and study.n_cases > MAX_CASES:
        raise InputError(f"the study has {study.n_cases:.3g} cases, at most {MAX_CASES:.0e}: "
                         f"lower study.samples or the grid sizes")
    _check_one_case(study)
    return study


def _samples(kind: str, st: dict) -> int | None:
    if kind in ("grid", "files"):
        if "samples" in st:
            raise InputError(f"study.samples does not apply to kind = \"{kind}\" (its cases "
                             f"are {'the grid' if kind == 'grid' else 'the files'})")
        return None
    if "samples" not in st:
        raise InputError(f"study.samples missing (kind = \"{kind}\" needs a sample count)")
    n = check_int("study.samples", st["samples"], 1, 10_000_000)
    return check_sobol_base(n) if kind == "sobol" else n


def _parameters(table, kind: str) -> list[Parameter]:
    if not isinstance(table, dict):
        raise InputError("parameters must be a table [parameters]")
    out = []
    for name, t in table.items():
        if not isinstance(name, str) or "." not in name or name.split(".", 1)[0] not in TABLES:
            raise InputError(f"parameters: {name!r} must be TABLE.KEY with TABLE one of "
                             f"{', '.join(TABLES)} (e.g. \"texture.alpha_deg\")")
        out.append(parse_parameter(name, t, "grid" if kind == "files" else kind))
    if kind == "files" and any(not p.name.startswith("contact.") for p in out):
        raise InputError("kind = \"files\" takes no [parameters] but contact.* ones (its "
                         "cases are the files, each at every point of their grid)")
    if kind not in ("files",) and not out:
        raise InputError(f"kind = \"{kind}\" needs at least one entry in [parameters]")
    if kind == "sobol" and len(out) < 2:
        raise InputError("kind = \"sobol\" needs at least two parameters to split a variance")
    return out


def _spec(st: dict, data: dict, kind: str, params, named: StudyFiles) -> dict:
    """The work of one case, as plain data (the workers rebuild texture and assembly)."""
    from ..microslip.risk import CONTACTS
    stages = st.get("stages", ["risk"] if "assembly" in st else
                    ["crawl"] if "crawl" in data else ["derive"])
    if isinstance(stages, str):
        stages = [stages]
    if isinstance(stages, list) and "crawl" in data and "crawl" not in stages:
        stages = [*stages, "crawl"]             # a [crawl] table: every case crawls
    if not isinstance(stages, list) or not stages:
        raise InputError(f"study.stages must be a list of {', '.join(STAGES)}")
    for i, s in enumerate(stages):
        check_choice(f"study.stages[{i}]", s, STAGES)
    stages = [s for s in STAGES if s in stages]
    spec = {"stages": stages, "texture": None, "texture_name": "", "assembly": None,
            "assembly_path": "", "contact": None, "directions": 72, "law": "star",
            "cycles": None, "tolerance": None, "output": None, "surface": {}}
    asm_data = named.assembly
    if asm_data is not None:
        spec["assembly"], spec["assembly_path"] = asm_data, str(named.path("study.assembly"))
    elif "risk" in stages:
        raise InputError("study.assembly missing: the risk stage needs an assembly file")
    spec["texture"], spec["texture_name"], contact = _texture(st, data, named, kind)
    if kind != "files" and spec["texture"] is None and ("derive" in stages or "fit" in stages):
        raise InputError("derive and fit need a texture: study.texture, a [texture] table or "
                         "an assembly whose [friction] table names one")
    if "contact" in st:
        contact = check_choice("study.contact", st["contact"], CONTACTS)
    spec["contact"] = contact
    if "directions" in st:
        spec["directions"] = check_int("study.directions", st["directions"], 8, 3600)
    if "law" in st:
        spec["law"] = check_choice("study.law", st["law"], ("star", "ellipse"))
    for k in ("cycles", "tolerance"):
        if k in st:
            spec[k] = check_range(f"study.{k}", st[k], 1.0 if k == "cycles" else 1e-12,
                                  1e15 if k == "cycles" else 1.0)
    from .crawl import crawl_spec
    crawl = crawl_spec(data, params, stages, spec["texture"] is not None or kind == "files")
    if crawl is not None:                  # (absent otherwise: older fingerprints hold)
        spec["crawl"] = crawl
    spec["output"] = _output(st, stages, bool(data.get("contact")) or any(
        p.name.startswith("contact.") for p in params))
    spec["surface"] = _surface_options(st, kind)
    from .contact import contact_spec
    elastic = contact_spec(data, params)
    if elastic is not None:                # (absent otherwise: older fingerprints hold)
        spec["elastic"] = elastic
    if elastic is not None and spec["texture"] is None and kind != "files":
        raise InputError("[contact] weighs the faces of a texture or scan by the contact "
                         "force: the study has none (study.texture, a [texture] table, or "
                         "kind = \"files\")")
    used = {p.name.split(".", 1)[0] for p in params}
    if "texture" in used and not isinstance(spec["texture"], dict):
        raise InputError("texture.* parameters need a wedge texture (a texture TOML or a "
                         "[texture] table)")
    if used & {"assembly", "friction", "loading"} and asm_data is None:
        raise InputError("assembly, friction and loading parameters need study.assembly")
    return spec


def _texture(st, data, named: StudyFiles, kind):
    """(texture table or surface file name or None, its name, contact of the assembly)."""
    contact = "all-faces"
    fr = (named.assembly or {}).get("friction", {})
    if isinstance(fr, dict) and isinstance(fr.get("contact"), str):
        contact = fr["contact"]
    if kind == "files":
        if "texture" in st or "texture" in data:
            raise InputError("kind = \"files\" takes its textures from study.files, not "
                             "study.texture")
        return None, "", contact
    if "texture" in st and "texture" in data:
        raise InputError("give study.texture or a [texture] table, not both")
    if "texture" in data:
        if not isinstance(data["texture"], dict):
            raise InputError("texture must be a table [texture]")
        return copy.deepcopy(data["texture"]), "[texture] of the study file", contact
    tp = named.path("study.texture")
    if tp is None and isinstance(fr, dict) and isinstance(fr.get("texture"), str):
        tp = named.path(assembly_key(st["assembly"], "texture"))
    if tp is None:
        return None, "", contact
    if str(tp).lower().endswith(".toml"):
        t = read_input_toml(tp, "texture file")
        if "texture" not in t or not isinstance(t["texture"], dict):
            raise InputError(f"{tp}: missing table [texture]")
        return t["texture"], str(tp), contact
    return str(tp), str(tp), contact      # a surface file: read on the workers


def _output(st: dict, stages: list, elastic: bool = False) -> str:
    from .cases import output_columns
    cols = [c for c, kind in output_columns(stages, elastic) if kind == "REAL"]
    default = "drift_per_cycle_m" if "risk" in stages else \
        "speed_body_lengths_per_period" if stages == ["crawl"] else "anisotropy"
    return check_choice("study.output", st.get("output", default), cols)


def _surface_options(st: dict, kind: str) -> dict:
    keys = ("unit", "pixel_size", "height_scale", "detrend", "mu", "max_slope", "despike",
            "despike_window")
    given = {k: st[k] for k in keys if k in st}
    if given and kind != "files":
        raise InputError(f"study.{next(iter(given))} reads scan files: it belongs to kind = "
                         f"\"files\"")
    _check_surface_options(given)
    return given


def _check_surface_options(o: dict) -> None:
    """The scan-reading keys checked once, here, with the readers' own checks (not in
    every case of the study)."""
    from ..surface import quality, topography
    from ..surface.facets import DETREND
    from ..surface.friction_map import MAX_MU
    try:
        f = topography.unit_factor(o["unit"]) if "unit" in o else 1.0
        if "pixel_size" in o:
            if "unit" not in o:
                raise InputError("pixel_size needs unit (the unit of the pixel size)")
            topography.pixel_pair(o["pixel_size"], f)
        if "height_scale" in o:
            topography.check_height_scale(o["height_scale"])
        if "detrend" in o:
            check_choice("detrend", o["detrend"], tuple(DETREND))
        if "mu" in o:
            check_range("mu", o["mu"], 0.0, MAX_MU)
        if "max_slope" in o:
            quality.check_max_slope(o["max_slope"])
        if "despike" in o or "despike_window" in o:
            if "despike" not in o:
                raise InputError("despike_window needs despike (the threshold K)")
            quality.check_despike(o["despike"], o.get("despike_window"))
    except InputError as exc:
        msg = str(exc)
        raise InputError(msg if msg.startswith("study.") else f"study.{msg}") from None


def _check_one_case(study: Study) -> None:
    """Build (not compute) the case at the parameters' medians: a parameter the texture or
    assembly does not have, or a value outside its range, is refused now."""
    from .cases import build_inputs
    values = {p.name: p.centre for p in study.parameters}
    if study.spec.get("crawl") is not None:
        from .crawl import check_case
        check_case(study.spec["crawl"], values)
    if study.kind == "files":
        if study.spec.get("elastic") is not None:
            from .contact import elastic_for
            elastic_for(study.spec["elastic"], values)
        return
    try:
        build_inputs(study.spec, values, None, weigh=False)
    except InputError as exc:
        at = "the grid's first values" if study.kind == "grid" else "their medians"
        raise InputError(f"parameters at {at} ({_show(values)}): {exc}") from None


def _show(values: dict) -> str:
    return ", ".join(f"{k} = {v:.6g}" for k, v in values.items())
