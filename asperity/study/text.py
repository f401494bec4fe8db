"""A study's summary as terminal text and as ``summary.md`` (what a person reads)."""
from __future__ import annotations

#: the store's solved_by values, as the summary says them
SOLVED_BY = {"closed-form": "the closed form", "exact": "the exact event solver"}


def _um(x) -> str:
    return "n/a" if x is None else f"{x * 1e6:+.4g} um"


def _um_abs(x) -> str:
    return "n/a" if x is None else f"{x * 1e6:.4g} um"


def _mm(x) -> str:
    return "n/a" if x is None else f"{x * 1e3:.4g} mm"


def _cycles(x) -> str:
    return "never" if x is None else f"{x:.4g}"


def _pct(n: int, total: int) -> str:
    return f"{100.0 * n / total:.1f} %" if total else "-"


def lines(s: dict) -> list[str]:
    """The summary as lines of text (the same for the terminal and summary.md)."""
    out = [f"study {s['name']} ({s['kind']}, {s['cases']} cases, seed {s['seed']}, stages "
           f"{', '.join(s['stages'])}): {s['completed']} completed, {s['failed']} failed, "
           f"{s['missing']} not run yet"]
    if s["missing"]:
        out.append("  (interrupted: run the same command again to resume)")
    for f in s.get("failures", [])[:3]:
        out.append(f"  failed x{f['cases']} (first: case {f['first_case']}): {f['message']}")
    answer = _answer(s)
    if answer:
        out.insert(1, answer)
    if "risk" in s["stages"]:
        v = s["verdicts"]
        out.append("verdicts: " + (", ".join(f"{k} {n} ({_pct(n, s['completed'])})"
                                              for k, n in v.items()) or "none"))
        if s.get("solved_by"):
            out.append("solved by: " + ", ".join(
                f"{SOLVED_BY.get(k, k)} {n}" for k, n in s["solved_by"].items()))
        p = s["p_ratchet"]
        if p is not None and p["low"] is None:
            out.append(f"share of the grid's cases that ratchet: {p['estimate']:.4f} (a grid "
                       f"is a design, not a random sample: no probability, no interval)")
        elif p is not None:
            out.append(f"probability of ratchet: {p['estimate']:.4f} (95 % interval "
                       f"{p['low']:.4f} - {p['high']:.4f})")
        d = s["drift_per_cycle_m"]
        if d:
            out.append(f"drift per cycle (signed, + towards +x): p05 {_um(d['p05'])}, p50 "
                       f"{_um(d['p50'])}, p95 {_um(d['p95'])}")
        c = s["creep_per_cycle_m"]
        if c:
            out.append(f"creep per cycle |drift|: p50 {_um_abs(c['p50'])}, p95 "
                       f"{_um_abs(c['p95'])}, p99 {_um_abs(c['p99'])}")
        a = s["drift_after_cycles_m"]
        if a:
            out.append(f"drift after the assessed life: p50 {_mm(a['p50'])}, p95 "
                       f"{_mm(a['p95'])}, p99 {_mm(a['p99'])}")
        t = s["cycles_to_tolerance"]
        if s.get("tolerance_m") is None:
            out.append("cycles until a tolerance is reached: no tolerance given (loading."
                       "tolerance in the assembly file or study.tolerance)")
        elif t:
            out.append(f"cycles until the tolerance of {_mm(s['tolerance_m'])} is reached: p05 "
                       f"{_cycles(t['p05'])}, p50 {_cycles(t['p50'])} (5 % of the cases reach "
                       f"it within the p05)")
    note = _quantile_note(s)
    if note:
        out.append(note)
    for k, label in (("anisotropy", "anisotropy"), ("asymmetry", "asymmetry (mu_a+ - mu_a-)/mean"),
                     ("principal_direction_deg", "principal direction (deg)")):
        q = s.get(k)
        if q:
            out.append(f"{label}: p05 {_g(q['p05'])}, p50 {_g(q['p50'])}, p95 {_g(q['p95'])}")
    out.extend(_influence_lines(s))
    if s.get("load_dependence"):
        from .contact import load_lines
        out.extend(load_lines(s["load_dependence"]))
    if s.get("crawl"):
        from .crawl_summary import crawl_lines
        out.extend(crawl_lines(s["crawl"], s["crawl"]["inputs"]))
    if s.get("ranking"):
        out.append("ranked (most at risk first):")
        for r in s["ranking"][:20]:
            out.append("  " + _rank_line(r))
        if len(s["ranking"]) > 20:
            out.append(f"  ... {len(s['ranking']) - 20} more (summary.md, --export)")
    out.append(f"store: {s['store']}")
    return out


def _answer(s: dict) -> str:
    """One sentence for the design engineer: how likely, how far, what matters most."""
    p = s.get("p_ratchet")
    if not p or "risk" not in s["stages"]:
        return ""
    if p["low"] is None:
        words = [f"answer: {100 * p['estimate']:.1f} % of the grid's cases ratchet"]
    else:
        words = [f"answer: {100 * p['estimate']:.1f} % of the cases ratchet (95 % interval "
                 f"{100 * p['low']:.1f}-{100 * p['high']:.1f} %)"]
    c = s.get("creep_per_cycle_m")
    if c and c.get("p95"):
        words.append(f"the 95th percentile creeps {_um_abs(c['p95'])} per cycle")
    t = s.get("cycles_to_tolerance")
    if t and t.get("p05") is not None and s.get("tolerance_m") is not None:
        words.append(f"5 % reach the {_mm(s['tolerance_m'])} tolerance within "
                     f"{_cycles(t['p05'])} cycles")
    from .summary import most_influential
    top = most_influential(s)
    if top:
        how = "Sobol ST" if s.get("sobol") else "rank correlation"
        words.append(f"{top[0]} matters most ({how})")
    elif s.get("output_varies") is False:
        words.append(s["influence_note"])
    return "; ".join(words)


def _quantile_note(s: dict) -> str:
    """With few cases the outer quantiles are the sample's extremes: say so."""
    n = s.get("completed") or 0
    if not (s.get("drift_per_cycle_m") or s.get("anisotropy")) or n >= 100:
        return ""
    if n < 20:
        return (f"  (with {n} completed cases, p05 and p95 are the smallest and largest values "
                f"and p99 the largest: quantiles need 20 cases, p99 100)")
    return f"  (with {n} completed cases, p99 is the largest value: it needs 100 cases)"


def _g(x) -> str:
    return "n/a" if x is None else f"{x:.4g}"


def _conf(v: dict, k: str) -> str:
    c = v[f"{k}_conf"]
    if c is None:
        return "(no interval)"
    return f"+- {c:.3f}" if c >= 0.0005 else f"+- {c:.1e}"     # never "+- 0.000"


def _influence_lines(s: dict) -> list[str]:
    out = []
    so = s.get("sobol")
    if so:
        out.append(f"Sobol indices of {s['output']} (first order S1, total ST, 95 % intervals):")
        for n, v in sorted(so.items(), key=lambda kv: -kv[1]["ST"]):
            line = (f"  {n:<28} S1 {v['S1']:+.3f} {_conf(v, 'S1')}   ST {v['ST']:.3f} "
                    f"{_conf(v, 'ST')}")
            out.append(line + (f"  ({v['note']})" if v.get("note") else ""))
        out += [f"  warning: {w}" for w in s.get("sobol_warnings") or []]
    rc = s.get("rank_correlation")
    if rc and not so and s.get("output_varies"):
        ci = s.get("rank_correlation_interval")
        how = "95 % intervals" if ci is not None else "over the grid, a design: no intervals"
        ranked = sorted(rc.items(), key=lambda kv: -(abs(kv[1]) if kv[1] is not None else -1))
        out.append(f"rank correlation with {s['output']} (Spearman, {how}): "
                   + ", ".join(f"{n} {_rank(v, (ci or {}).get(n), ci is not None)}"
                               for n, v in ranked))
    if s.get("influence_note"):
        out.append(s["influence_note"] if s.get("output_varies") is False else
                   f"which parameter matters: {s['influence_note']}")
    elif s.get("most_influential"):
        how = "Sobol ST" if so else "rank correlation"
        out.append(f"which parameter matters: {', '.join(s['most_influential'])} (by {how}, "
                   f"most first)")
    return out


def _rank(v, ci, random: bool) -> str:
    if v is None:
        return "n/a (does not vary)"
    if not random:
        return f"{v:+.3f}"
    if ci is None:
        return f"{v:+.3f} (every case in this order)" if abs(v) == 1.0 else f"{v:+.3f}"
    return f"{v:+.3f} ({ci['low']:+.2f} to {ci['high']:+.2f})"


def short_path(path: str) -> str:
    """A file name relative to the current folder when that is shorter."""
    import os
    try:
        rel = os.path.relpath(path)
    except ValueError:
        return path
    return rel if len(rel) < len(path) else path


def _rank_line(r: dict) -> str:
    if r["status"] != "ok":
        return f"{r['rank']:>4}. {short_path(r['file'])}: {r['status']}: {r['message']}"
    bits = [] if r.get("pressure_Pa") is None else [f"p {r['pressure_Pa']:.3g} Pa"]
    if r.get("verdict") is not None:
        bits.append(f"{r['verdict']} {_um(r.get('drift_per_cycle_m'))}/cycle")
    if r.get("anisotropy") is not None:
        bits.append(f"anisotropy {r['anisotropy']:.3g}")
    if r.get("asymmetry") is not None:
        bits.append(f"asymmetry {r['asymmetry']:+.3g}")
    if r.get("principal_direction_deg") is not None:
        bits.append(f"t_a {r['principal_direction_deg']:.1f} deg")
    return f"{r['rank']:>4}. {short_path(r['file'])}: " + ", ".join(bits)


def _md_conf(c) -> str:
    if c is None:
        return "no interval"
    return f"+- {c:.4f}" if c >= 0.00005 else f"+- {c:.1e}"


def markdown(s: dict, figures: list[str]) -> str:
    """summary.md: the text lines, the Sobol table and the figures."""
    md = [f"# Study {s['name']}", "", "```", *lines(s), "```", ""]
    if s.get("parameters"):
        md += ["## Parameters", "", "| parameter | distribution |", "|---|---|"]
        md += [f"| `{n}` | {d} |" for n, d in s["parameters"].items()]
        md.append("")
    if s.get("sobol"):
        md += ["## Sobol indices", "", f"Output: `{s['output']}`.", "",
               "| parameter | S1 | S1 95 % | ST | ST 95 % |", "|---|---|---|---|---|"]
        for n, v in sorted(s["sobol"].items(), key=lambda kv: -kv[1]["ST"]):
            md.append(f"| `{n}` | {v['S1']:.4f} | {_md_conf(v['S1_conf'])} | {v['ST']:.4f} | "
                      f"{_md_conf(v['ST_conf'])} |")
        md.append("")
    if s.get("ranking"):
        md += ["## Ranking", "", "| rank | file | status | verdict | drift per cycle (um) | "
               "anisotropy | asymmetry |", "|---|---|---|---|---|---|---|"]
        for r in s["ranking"]:
            d = r.get("drift_per_cycle_m")
            md.append(f"| {r['rank']} | `{r['file']}` | {r['status']} | {r.get('verdict') or ''}"
                      f" | {'' if d is None else f'{d * 1e6:+.4g}'} | "
                      f"{_g(r.get('anisotropy'))} | {_g(r.get('asymmetry'))} |")
        md.append("")
    if figures:
        md += ["## Figures", ""] + [f"![{f}]({f})" for f in figures] + [""]
    return "\n".join(md)
