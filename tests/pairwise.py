"""Covering arrays of strength 2 ("all pairs") for the option tests.

``covering_array(factors, allowed)`` returns rows (dicts, one level of each factor) such
that every pair of levels of any two factors that some allowed row can hold appears in at
least one row: a few rows instead of the product.  Greedy, as AETG (Cohen et al., IEEE TSE
23, 1997) but over the whole allowed product (small here): each new row is the allowed
row that covers the most pairs not yet covered, ties broken by a seeded shuffle, so the
array is the same on every run.  No dependency: allpairspy would do it too, but the
constraint handling here (a predicate over whole rows) is ten lines."""
from __future__ import annotations

import itertools
import random


def pairs_of(row: tuple) -> set:
    """The (factor index, level index) pairs a row (of level indices) covers."""
    return {((i, row[i]), (j, row[j])) for i, j in itertools.combinations(range(len(row)), 2)}


def covering_array(factors: dict, allowed=None, seed: int = 0,
                   max_product: int = 200_000) -> list[dict]:
    """Rows covering every feasible pair of levels; ``allowed(row_dict) -> bool`` rejects a
    combination (its pairs are then required only if another allowed row holds them)."""
    names = list(factors)
    levels = [list(factors[n]) for n in names]
    size = 1
    for lv in levels:
        size *= len(lv)
    if size > max_product:
        raise ValueError(f"{size} combinations: too many to enumerate")
    rows = [r for r in itertools.product(*(range(len(lv)) for lv in levels))
            if allowed is None or allowed(dict(zip(names, (levels[i][k]
                                                            for i, k in enumerate(r)))))]
    if not rows:
        raise ValueError("no combination is allowed")
    random.Random(seed).shuffle(rows)
    todo = set().union(*(pairs_of(r) for r in rows))
    chosen = []
    while todo:
        best = max(rows, key=lambda r: len(pairs_of(r) & todo))
        todo -= pairs_of(best)
        chosen.append(best)
    return [dict(zip(names, (levels[i][k] for i, k in enumerate(r)))) for r in chosen]


def ids(rows: list[dict]) -> list[str]:
    """Short test ids of rows: the levels joined."""
    return ["-".join(str(v) for v in r.values()) for r in rows]
