"""Triage of the mutation campaign's survivors (benchmarks/mutation_campaign.py), by mutant
id (module:operator:hash of the line's text and column; ``--survivors`` lists them).

EQUIVALENT: survivors no test can kill, each with the reason (the mutant computes the same
numbers, or differs only where no input can reach).  They leave the score's denominator.
LEFT: real survivors left without a test, with the reason (e.g. the body solver's Newton
iteration, rewritten meanwhile: listed for the lead, not pinned by tests of code that goes).
"""

EQUIVALENT: dict[str, str] = {
}

LEFT: dict[str, str] = {
}
