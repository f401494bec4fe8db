"""The parser of every ``asperity`` command: argparse with the project's rules.

* A number typed with a minus sign is a value, whatever its form: ``--force -1e-1 0``,
  ``--elastic -1e9``, ``--angle -.5``, ``--u0 -inf`` (argparse alone knows only ``-1`` and
  ``-1.5`` and takes ``-1e9`` for an unknown option).  The command then checks its range.
* A flag is spelled in full: no abbreviations (``contact --mu`` is an unknown flag, not
  "ambiguous: --mu-alpha or --mu-beta"; a script's ``--pres`` would change meaning the
  day a flag ``--preset`` appears).
* Exit status (README, "Errors"): a value the command cannot use -- text where a number
  belongs, a number out of its range, a word that is not one of the choices, a file that
  cannot be read -- is one line and status 1 (:data:`EXIT_VALUE`), whether argparse or
  the command finds it; a command line that cannot be parsed -- an unknown command or
  flag, a flag without its value, a missing argument, two flags that exclude each other
  -- is one line and status 2 (:data:`EXIT_USAGE`).
"""
from __future__ import annotations

import argparse
import math
import re

#: a bad value (also the status of every AsperityError)
EXIT_VALUE = 1
#: a command line that cannot be parsed
EXIT_USAGE = 2

#: a number as typed, with its minus sign: digits with or without a point, an exponent,
#: an infinity or NaN (a value, never an option)
NEGATIVE_NUMBER = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$",
                             re.IGNORECASE)
#: a whole number typed as such (read exactly, whatever its size)
_WHOLE = re.compile(r"^[-+]?\d+$")


def flag_of(action) -> str:
    """The name a message gives an argument: its long flag, else its metavar or dest."""
    if action.option_strings:
        return max(action.option_strings, key=len)
    m = action.metavar
    return m if isinstance(m, str) else action.dest


class Parser(argparse.ArgumentParser):
    """argparse with a one-line usage error (status 2; the usage itself is in --help),
    negative numbers in any form taken as values, flags in full, and a bad value
    (argparse's type and choice errors) refused as the commands refuse one: an
    InputError, status 1."""

    def __init__(self, *args, **kwargs):
        kwargs.setdefault("allow_abbrev", False)
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = NEGATIVE_NUMBER

    def parse_args(self, args=None, namespace=None):
        """As argparse's, but arguments left over are reported by the subcommand's parser
        (``asperity contact: error: unrecognized arguments ... (see asperity contact
        --help)``), not by the top-level one."""
        ns, extra = self.parse_known_args(args, namespace)
        if extra:
            sub = self
            if self._subparsers is not None and getattr(ns, "command", None):
                sub = self._subparsers._group_actions[0].choices.get(ns.command, self)
            sub.error(f"unrecognized arguments: {' '.join(extra)}")
        return ns

    def error(self, message: str):
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message} (see {self.prog} --help)\n")

    def _get_value(self, action, arg_string):
        from ..errors import number_from_text
        if action.type is float:
            return number_from_text(flag_of(action), arg_string)
        if action.type is int:
            # a whole number as typed (2**63 - 1 exactly, not through a float); any other
            # number goes on as it is, for the command's check_int to refuse with the
            # flag's range ("--max-iterations must be a whole number in [1, 1000000]")
            text = str(arg_string).strip()
            if _WHOLE.match(text):
                return int(text)
            x = number_from_text(flag_of(action), text)
            return int(x) if math.isfinite(x) and x.is_integer() else x
        return super()._get_value(action, arg_string)

    def _check_value(self, action, value):
        if action.choices is None or isinstance(action, argparse._SubParsersAction):
            return super()._check_value(action, value)    # an unknown command: usage
        if value not in action.choices:
            from ..errors import check_choice
            check_choice(flag_of(action), value, [str(c) for c in action.choices])


def value_options(parser: argparse.ArgumentParser):
    """Every (subcommand, action) of ``parser`` whose flag takes values (tests walk them)."""
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    for name, p in sub.choices.items():
        for a in p._actions:
            if a.option_strings and a.nargs != 0:
                yield name, p, a


class DefaultsHelpFormatter(argparse.ArgumentDefaultsHelpFormatter):
    """Defaults in the help, but not "(default: None)" (derive's help said it 34 times):
    those options say in words what leaving them out means; nor "(default: False)" after
    a switch (--json, -q)."""

    def _get_help_string(self, action):
        if action.default is None or (action.nargs == 0 and action.default is False):
            return action.help
        return super()._get_help_string(action)


#: the componentwise law's flags (forward = +t_a, backward = -t_a, transverse = +-t_b)
COMPONENTWISE_FLAGS = (("mu_f", "--mu-f", "forward (+t_a, towards the head)"),
                       ("mu_b", "--mu-b", "backward (-t_a)"),
                       ("mu_t", "--mu-t", "transverse (+-t_b)"))


def add_componentwise_flags(p, what: str = "--law componentwise") -> None:
    """--mu-f --mu-b --mu-t: the three coefficients of the componentwise law (Hu et al.)."""
    for _, flag, words in COMPONENTWISE_FLAGS:
        p.add_argument(flag, type=float, metavar="MU",
                       help=f"{what}: {words} friction coefficient, in [1e-6, 100]")


def componentwise_given(args) -> bool:
    return any(getattr(args, d, None) is not None for d, _, _ in COMPONENTWISE_FLAGS)


def componentwise_from_args(args):
    """The componentwise PlanarLaw of --mu-f --mu-b --mu-t (all three required)."""
    from ..errors import InputError
    from ..laws.geometry import MU_MAX, MU_MIN
    from ..laws.planar import componentwise_law
    from .sources import flag_names
    for dest, flag, words in COMPONENTWISE_FLAGS:
        if getattr(args, dest, None) is None:
            raise InputError(f"the componentwise law needs {flag} ({words} friction "
                             f"coefficient, in [{MU_MIN:g}, {MU_MAX:g}])")
    with flag_names({dest + " ": flag + " " for dest, flag, _ in COMPONENTWISE_FLAGS}):
        return componentwise_law(*(getattr(args, d) for d, _, _ in COMPONENTWISE_FLAGS))
