"""The terminal text of a risk verdict and of a risk map."""
from __future__ import annotations


def _len(x) -> str:
    if x is None:
        return "-"
    a = abs(x)
    if a == 0:
        return "0 m"
    if a >= 1e-2:
        return f"{x:+.4g} m"
    if a >= 1e-5:
        return f"{x * 1e3:+.4g} mm"
    return f"{x * 1e6:+.4g} um"


def _cycles(n) -> str:
    """A number of cycles as the web page writes it (1,000,000; 364; 2.5e+09)."""
    x = float(n)
    return f"{int(x):,}" if x.is_integer() and abs(x) < 1e9 else f"{x:.4g}"


def format_text(out: dict) -> str:
    a = out["assembly"]
    f = out["friction"]
    L = out["loading"]

    def mu(x):
        return "inf (self-locking)" if x is None else f"{x:.6f}"
    size = (f"strip, {a['n']} nodes, l = {a['l']:g} m" if a["model"] == "strip"
            else f"two-node, l0 = {a['l0']:g} m")
    src = {"explicit": "explicit coefficients",
           "gauge": f"gauge {f.get('gauge', '')}",
           "texture": f"texture {f.get('texture', '')} ({f.get('contact', '')})"}[f["source"]]
    lines = [f"assembly: {a['name']} ({size})", f"friction: {src}"]
    if f["source"] != "explicit":
        lines.append(f"  slip axis +x at {f['slip_axis_deg']:g} deg in the texture frame "
                     f"({f['slip_axis']}), texture on the {f['textured']}")
    if f.get("note"):
        lines.append(f"  ({f['note']})")
    cp = f.get("contact_pressure")
    if cp:
        lines.append(f"  {pressure_words(cp)}")
    if f.get("elastic_contact"):
        from ..surface.contact_facets import contact_lines
        lines += ["  " + x for x in contact_lines(f["elastic_contact"])]
    lines.append(f"  mu+ (assembly sliding towards +x) = {mu(f['mu_plus'])}   "
                 f"mu- (towards -x) = {mu(f['mu_minus'])}")
    hist = " -> ".join(f"{x:g}" for x in L["history_K"])
    Fmax = out["max_tangential_load"]
    lines.append(f"loading: dT {hist} K per cycle, "
                 + (f"tangential load up to {Fmax:g} {L['force_unit']} ({L['force_at']})"
                    if Fmax else "no tangential load"))
    dc = out["dT_c_K"]
    cf = out["dT_c_closed_form_K"]
    lines.append("elastic limit dT_c = " + ("inf (no slider ever slips)" if dc is None else
                 f"{dc:.4g} K" + (f" (closed form {cf:.4g} K)" if cf is not None else ""))
                 + f"; dT range {out['dT_range_K']:g} K; margin dT_range / (2 dT_c) = "
                 f"{out['margin']:.3g}")
    v = out["verdict"]
    if v == "slides-off":
        lines.append(f"verdict: SLIDES OFF -- {out['reason']}")
    else:
        lines += verdict_lines(out, v)
        if out.get("warning"):
            lines.append(f"  WARNING: {out['warning']}")
        if a["model"] == "strip" and v == "alternating-slip" and out["margin"] > 1:
            lines.append("  (for a strip, margin > 1 is necessary but not sufficient: its ends "
                         "slip back and forth while its middle sticks)")
        lines.extend(near_symmetric_notes(out))
    dyn = out.get("dynamic")
    if dyn:
        rel = dyn["relative_difference"]
        lines.append(f"Moreau time-stepping ({dyn['steps_per_segment']} steps per load segment, "
                     f"{dyn['cycles']} cycles): drift {_len(dyn['drift_per_cycle_m'])} per cycle"
                     + (f", {rel:.2g} from the quasi-static value" if rel is not None else
                        f" (quasi-static: none; difference {_len(dyn['difference_m'])})")
                     + f"; solver {dyn['solver'].get('status', '?')}")
    lines.append(f"sign convention: {out['sign_convention']}")
    return "\n".join(lines)


def verdict_lines(out: dict, v: str) -> list:
    """The verdict in the web page's order: what it means, then the cycles to the tolerance,
    the drift per cycle, the drift after the cycles assessed (flagged when it is longer
    than the part) and what its extrapolation ignores."""
    st = out["stabilised_at_cycle"]
    a = out["assembly"]
    lines = [{"ratchet": f"verdict: RATCHET -- the assembly walks a little in every load "
                         f"cycle, always the same way (towards {out['drift_direction']}): the "
                         "drift adds up over its life",
              "alternating-slip": "verdict: ALTERNATING SLIP -- sliders slip back and forth "
                                  "every cycle (fretting), no net drift: wear at the ends, "
                                  "no walk",
              "shakedown": "verdict: SHAKEDOWN -- no slip after the first cycles, no drift: "
                           "the assembly settles and stays"}[v]]
    tol, c = out["tolerance_m"], out["cycles_to_tolerance"]
    lines.append("  cycles to tolerance: " + (
        "- (no tolerance given: --tolerance MM or the file's loading.tolerance)" if tol is None
        else f"{'never' if c is None else _cycles(c)} (until a drift of {tol * 1e3:g} mm)"))
    lines.append(f"  drift per cycle: {_len(out['drift_per_cycle_m'])} ("
                 + (f"of the stabilised cycle, from cycle {st}" if st else
                    "of the last cycle marched: NOT stabilised") + "; + is towards +x)")
    n = _cycles(out["cycles"]) + (" cycle" if out["cycles"] == 1 else " cycles")
    after = out["drift_after_cycles_m"]
    length = a.get("l", a.get("l0"))
    beyond = bool(length) and abs(after) > length
    lines.append(f"  drift after {n}: {_len(after)} ("
                 + (f"extrapolated from {out['cycles_marched']} marched cycles: see below"
                    if out.get("extrapolated") else "marched cycle by cycle") + ")"
                 + (f"; MORE THAN THE PART'S LENGTH ({_len(length)[1:]})" if beyond else ""))
    if out.get("extrapolated"):
        lines.append(f"  (the drift after {n} carries the stabilised cycle's drift on: "
                     "it ignores what changes over a life (wear, friction, temperatures) and "
                     "any stop or clearance that holds the part"
                     + (f"; at {_len(after)} it is more than the part's length "
                        f"({_len(length)[1:]}): the tolerance is used up long before, so read "
                        "it as a rate only" if beyond else "") + ")")
    return lines


def near_symmetric_notes(out: dict) -> list:
    """Notes on what nearly symmetric friction means for the verdict."""
    r = out.get("asymmetry")
    res = out.get("resolution")
    if res:
        odd = res["nodes"] % 2
        return [f"  NOTE: mu+ and mu- differ by {abs(r):.2g} of their value, less than the "
                f"{res['asymmetry_resolved']:.2g} that {res['nodes']} nodes resolve: the whole "
                f"strip slides about a node, so the nodes decide the drift ("
                + ("the middle one holds the imbalance: none" if odd else
                   "the two middle ones take turns: about an element's expansion per cycle")
                + f"); the continuum drifts at most "
                f"{_len(res['continuum_drift_bound_m'])[1:]} per cycle: assembly.n >= "
                f"{res['nodes_to_resolve']} resolves it"]
    if r and abs(r) < 1e-3 and out["verdict"] == "ratchet" \
            and out["assembly"]["model"] == "two-node":
        return [(f"  NOTE: mu+ and mu- differ by only {abs(r):.2g} of their value; the "
                f"two-node model ratchets by the full amount for any difference (the weaker "
                f"slider caps the bar force), so the direction rests on the sign of that "
                f"difference: check it against the scatter of the measurement")]
    return []


def format_map(out: dict) -> str:
    m = out["map"]
    px, py = m["x"]["parameter"], m["y"]["parameter"]
    head = f"{py} \\ {px}"
    lines = [(f"risk map: {out['assembly']['name']}, drift per cycle (um; S = shakedown, "
             f"A = alternating slip, X = slides off), {out['contact']}, texture on the "
             f"{out['textured']}"),
             f"{head:>14s} " + " ".join(f"{x:>9.4g}" for x in m["x"]["values"])]
    for y, vs, ds in zip(m["y"]["values"], m["verdict"], m["drift_per_cycle_m"]):
        cells = []
        for v, d in zip(vs, ds):
            mark = {"shakedown": "S", "alternating-slip": "A", "slides-off": "X"}.get(v)
            cells.append(f"{mark:>9s}" if mark else f"{d * 1e6:>+9.3g}")
        lines.append(f"{y:>14.4g} " + " ".join(cells))
    lines.append(f"sign convention: {out['sign_convention']}")
    return "\n".join(lines)


def pressure_words(cp: dict) -> str:
    """The line saying at which contact pressure the friction was taken, and how."""
    head = f"contact pressure {cp['pressure_Pa']:g} Pa ({cp['from']}): "
    if "members_Pa" in cp:
        from ..laws.family import how_words
        return head + how_words(cp)
    if cp.get("solved"):
        return head + "the elastic contact solved at it" + (
            f"; {cp['note']}" if cp.get("note") else "")
    return head + cp.get("note", "")
