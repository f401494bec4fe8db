"""Moreau time steps per second of one point mass sliding with each friction law.

Run as a script to print the figures (measured three times: the machine may be shared):
    python benchmarks/bench_moreau.py
Targets (issue 5): >= 1e6 steps/s for the ellipse law, >= 3e5 for the star-shaped law.
"""
from __future__ import annotations


def main(repeats: int = 3, seconds: float = 1.0) -> None:
    from asperity.bench import bench_moreau
    runs = [bench_moreau(seconds) for _ in range(repeats)]
    for name in runs[0]:
        rates = [r[name]["steps_per_second"] for r in runs]
        print(f"{name:38s}: " + "  ".join(f"{x:.3e}" for x in rates)
              + f"  steps/s (mean {runs[0][name]['mean_iterations']:.2f} iterations/step)")


if __name__ == "__main__":
    main()
