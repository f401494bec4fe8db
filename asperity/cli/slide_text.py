"""The text of ``asperity slide --body`` (kept apart from the command's options)."""
from __future__ import annotations

import math


def say_body(say, obj) -> None:
    """The text of a body's slide."""
    from ..dynamics.body_api import body_words
    b = obj["body"]
    say(body_words(b))
    th = obj["final_angle_rad"]
    if obj["rest"] is not None:
        say(f"rest at ({obj['rest'][0]:.6g}, {obj['rest'][1]:.6g}) m, angle {th:.6g} rad "
            f"({math.degrees(th):.4g} deg), after {obj['stop_time']:.6g} s ({steps_words(obj)}), "
            f"distance {obj['distance']:.6g} m")
    else:                        # t_end None: no rest within the horizon of the launch
        say(f"still moving at t = {obj['t_end'] or obj['steps'] * obj['dt']:g} s: position "
            f"({obj['final_position'][0]:.6g}, {obj['final_position'][1]:.6g}) m, angle "
            f"{th:.6g} rad ({math.degrees(th):.4g} deg)")
    ts, tw = obj["slide_stop_time"], obj["spin_stop_time"]
    words = ["did not slide" if ts == 0 and obj["u0"] == 0 else
             f"sliding stopped at {ts:.6g} s" if ts is not None else "still sliding",
             "did not spin" if tw == 0 and obj["omega0"] == 0 else
             f"spin stopped at {tw:.6g} s" if tw is not None else "still spinning"]
    if obj["together"] is not None:
        words.append("together" if obj["together"] else "not together")
    say(", ".join(words))
    if obj["terminal_ratio"] is not None:
        from ..bodies.closed_forms import TERMINAL_RATIO
        ref = TERMINAL_RATIO.get(b["kind"])
        say(f"terminal ratio v/(R omega): {obj['terminal_ratio']:.4g} (closed form of a "
            f"uniformly loaded {b['kind']}: {ref:.4g})")
    if obj["load"] is not None:
        ld = obj["load"]
        if ld["drift_per_cycle"] is not None:
            say(f"per cycle ({ld['cycles']} cycles): drift ({ld['drift_per_cycle'][0]:.6g}, "
                f"{ld['drift_per_cycle'][1]:.6g}) m, rotation {ld['rotation_per_cycle']:.6g} rad")
        if ld["drift_velocity"] is not None:
            say(f"mean drift velocity ({ld['drift_velocity'][0]:.6g}, "
                f"{ld['drift_velocity'][1]:.6g}) m/s, rotation rate {ld['rotation_rate']:.6g} "
                "rad/s")


def steps_words(obj) -> str:
    """The steps to the rest, and the run's end when it went on (--t-end): 'after 0.17 s
    (1699 steps of 0.0001 s; run to 1 s)', not '(10000 steps ...)' beside 0.17 s."""
    k = round(obj["stop_time"] / obj["dt"])
    more = f"; run to {obj['steps'] * obj['dt']:.6g} s" if obj["steps"] > k else ""
    return f"{k} step{'s' * (k != 1)} of {obj['dt']:g} s{more}"
