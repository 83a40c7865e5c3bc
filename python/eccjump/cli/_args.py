"""The parser and the argument types shared by the subcommands: each type checks its range and
says it in the units of the command line; every parse error is one short line."""

from __future__ import annotations

import argparse
import difflib
import math
import re
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, NoReturn, get_args

from eccjump._base.checks import MAX_MESSAGE, Integrator, short

#: Which pair to pick, in one sentence (benches/bench_pairs.py measures it): the same words in
#: the README, the docstrings and ``--help``.
PAIR_CHOICE = (
    "For speed pick Vern9 (at the default rtol 1.5-1.9x faster than RK45 and about 15x more "
    "accurate); keep RK45 for step-for-step parity with scipy."
)

#: The choices of ``--integrator`` (the Runge-Kutta pairs).
INTEGRATORS: tuple[str, ...] = get_args(Integrator)


#: A negative number as ``float`` reads it ("-1e-3", "-.5", "-1_000", "-inf", "-nan").
#: argparse's own pattern (``^-\d+$|^-\d*\.\d+$``) misses exponents and infinities and takes
#: ``--omega0 -1e-3`` for an option followed by another option.
NEGATIVE_NUMBER = re.compile(
    r"^-(?:(?:\d[\d_]*\.?[\d_]*|\.\d[\d_]*)(?:e[-+]?\d+)?|inf(?:inity)?|nan)$", re.IGNORECASE
)

#: A quoted value longer than this is cut in error messages (argparse quotes the whole value).
_QUOTED = re.compile(r"'([^']{40,})'")


class Parser(argparse.ArgumentParser):
    """An ``ArgumentParser`` that reads negative numbers as values, suggests the close
    spelling of an unknown option, and keeps every error to one line of at most
    :data:`MAX_MESSAGE` characters (its subcommands' parsers are of this class too)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = NEGATIVE_NUMBER

    def parse_known_args(  # type: ignore[override]
        self, args: Sequence[str] | None = None, namespace: argparse.Namespace | None = None
    ) -> tuple[argparse.Namespace, list[str]]:
        # The option names are checked first: a misspelt option is named (with its close
        # spelling) before argparse reports a required option or the subcommand as missing.
        args = sys.argv[1:] if args is None else list(args)
        unknown = [a for a in args[: self._end_of_options(args)] if self._is_unknown_option(a)]
        if unknown:
            self.error(self.unrecognized(unknown, "options"))
        return super().parse_known_args(args, namespace)

    def parse_args(  # type: ignore[override]
        self, args: Sequence[str] | None = None, namespace: argparse.Namespace | None = None
    ) -> argparse.Namespace:
        ns, extras = self.parse_known_args(args, namespace)
        if extras:  # reported by the subcommand's parser: its usage, its options
            target = self._subcommand(ns) or self
            target.error(target.unrecognized(extras))
        return ns

    def error(self, message: str) -> NoReturn:
        """Usage, then ``prog: error: message`` on one line of at most MAX_MESSAGE."""
        self.print_usage()
        line = one_line(f"{self.prog}: error: {_QUOTED.sub(_cut_quoted, message)}")
        self.exit(2, line + "\n")

    def unrecognized(self, extras: Sequence[str], what: str = "arguments") -> str:
        """The message "unrecognized arguments: ...", with the close spelling of the first
        unknown option."""
        text = f"unrecognized {what}: " + " ".join(short_text(a) for a in extras[:4])
        for arg in extras:
            hint = self.suggest(arg)
            if hint:
                return f"{text} (did you mean {hint}?)"
        return text

    def suggest(self, arg: str) -> str | None:
        """The option closest to ``arg`` (``--mu_s`` -> ``--mu-s``), or None."""
        name = arg.split("=", 1)[0]
        if not name.startswith("-") or NEGATIVE_NUMBER.match(name):
            return None
        # compared without the leading dashes, which every long option shares
        options = {o.lstrip("-"): o for o in self._option_string_actions if o.startswith("--")}
        word = name.lstrip("-").replace("_", "-")
        close = difflib.get_close_matches(word, list(options), n=1, cutoff=0.6)
        return options[close[0]] if close else None

    def _is_unknown_option(self, arg: str) -> bool:
        """Whether ``arg`` is an option (not a negative number) that this parser does not know,
        not even as an abbreviation (an ambiguous one is left to argparse)."""
        if not arg.startswith("-") or arg == "-" or NEGATIVE_NUMBER.match(arg):
            return False
        known = self._option_string_actions
        if arg.startswith("--"):
            name = arg.split("=", 1)[0]
            return not any(o.startswith(name) for o in known)
        # -x, or -xVALUE / -qo (a short option with its value, or short flags together)
        return arg[1:2].isalpha() and arg[:2] not in known

    def _end_of_options(self, args: Sequence[str]) -> int:
        """Where this parser's own options end in ``args``: at ``--`` (after it, everything
        is a value), or, with subcommands, at the subcommand (the first non-option)."""
        for i, arg in enumerate(args):
            if arg == "--" or (self._subparsers is not None and not arg.startswith("-")):
                return i
        return len(args)

    def _subcommand(self, ns: argparse.Namespace) -> Parser | None:
        """The parser of the subcommand ``ns`` was parsed by, if any."""
        for action in self._subparsers._group_actions if self._subparsers else ():
            if isinstance(action, argparse._SubParsersAction):
                parser = action.choices.get(getattr(ns, action.dest, None) or "")
                return parser if isinstance(parser, Parser) else None
        return None


def _cut_quoted(m: re.Match[str]) -> str:
    return f"'{m.group(1)[:37]}...'"


def one_line(text: str) -> str:
    """``text`` on one line of at most :data:`MAX_MESSAGE` characters."""
    text = " ".join(text.split())
    return text if len(text) <= MAX_MESSAGE else text[: MAX_MESSAGE - 3] + "..."


def short_text(text: str, width: int = 40) -> str:
    """A command-line value for a message: on one line, at most ``width`` characters, cut in
    the middle (the end of a path names the file)."""
    text = " ".join(str(text).split()) or repr(text)
    if len(text) <= width:
        return text
    head = (width - 3) // 3
    return f"{text[:head]}...{text[len(text) - (width - 3 - head) :]}"


def add_integrator(p: argparse._ActionsContainer, when: str = "") -> None:
    """``--integrator {RK45,DOP853,Vern9}`` (default RK45); ``when`` says where it
    applies."""
    p.add_argument(
        "--integrator",
        choices=INTEGRATORS,
        default="RK45",
        help=f"Runge-Kutta pair{when}: RK45 (Dormand-Prince 5(4), default: scipy's steps "
        "exactly), DOP853 (8(5,3)) or Vern9 (Verner 9(8)). " + PAIR_CHOICE,
    )


def directory(text: str) -> Path:
    """A directory option: an empty name is refused (``Path("")`` would be the current
    directory)."""
    if not text.strip():
        raise argparse.ArgumentTypeError(f"{text!r} names no directory")
    return Path(text)


def int_in(lo: int, hi: int | None = None) -> Callable[[str], int]:
    """An integer option in [lo, hi] (hi None: no upper bound here, the library has one)."""
    allowed = f"[{lo}, {'inf' if hi is None else hi}]"

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"{short_text(text)!r} is not an integer in {allowed}"
            ) from None
        if value < lo or (hi is not None and value > hi):
            raise argparse.ArgumentTypeError(
                f"{short(value)} is outside the allowed range {allowed}"
            )
        return value

    parse.__name__ = f"integer in {allowed}"
    return parse


def int_at_least(lo: int) -> Callable[[str], int]:
    """An integer option ≥ lo."""
    return int_in(lo)


def degrees_in(lo: float, hi: float) -> Callable[[str], float]:
    """An angle option in degrees, within [lo, hi]."""

    def parse(text: str) -> float:
        value = float(text)
        if not (lo <= value <= hi):
            raise argparse.ArgumentTypeError(
                f"{short(value)} is outside the allowed range [{lo:g}, {hi:g}] deg"
            )
        return value

    parse.__name__ = "degrees"
    return parse


def real_in(lo: float, hi: float, unit: str) -> Callable[[str], float]:
    """A real option within [lo, hi] in ``unit`` (NaN and infinities refused)."""

    def parse(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"{short_text(text)!r} is not a number in [{lo:g}, {hi:g}] {unit}".rstrip()
            ) from None
        if not lo <= value <= hi:
            raise argparse.ArgumentTypeError(
                f"{short(value)} is outside the allowed range [{lo:g}, {hi:g}] {unit}".rstrip()
            )
        return value

    parse.__name__ = f"number in {unit}" if unit else "number"
    return parse


#: The largest value an angle option in degrees may be read as radians of: a ramp angle
#: (π/2) and any other angle (2π).
RAMP_RADIANS = math.pi / 2
TURN_RADIANS = 2 * math.pi


def radians_hint(option: str, degrees: Sequence[float], up_to: float = TURN_RADIANS) -> None:
    """A note on stderr when the values of an angle option in degrees look like radians:
    none above ``up_to`` and one not 0 (an angle of a degree or so is rare; radians are
    what Python takes)."""
    if not degrees or any(not abs(x) <= up_to for x in degrees) or not any(degrees):
        return
    given = " ".join(f"{x:g}" for x in degrees)
    meant = " ".join(f"{math.degrees(x):.6g}" for x in degrees)
    print(
        f"note: {option} is in degrees: {given} deg; for {given} rad write {option} {meant}",
        file=sys.stderr,
    )


class Degrees(argparse.Action):
    """An angle option in degrees: its values are read by ``type`` (by default
    :func:`degrees_in` over [lo, hi]) and noted by :func:`radians_hint` when they look like
    radians (up to ``radians_up_to``). Every option whose help says ``[deg]`` is one (the
    tests check it), so that no angle option forgets the note."""

    def __init__(
        self,
        option_strings: Sequence[str],
        dest: str,
        *,
        lo: float = -math.inf,
        hi: float = math.inf,
        radians_up_to: float = TURN_RADIANS,
        **kwargs: Any,
    ) -> None:
        kwargs.setdefault("type", degrees_in(lo, hi))
        super().__init__(option_strings, dest, **kwargs)
        self.radians_up_to = radians_up_to

    def __call__(
        self,
        parser: argparse.ArgumentParser,
        namespace: argparse.Namespace,
        values: Any,
        option_string: str | None = None,
    ) -> None:
        shown = values if isinstance(values, list) else [values]
        radians_hint(option_string or self.dest, shown, self.radians_up_to)
        setattr(namespace, self.dest, values)


def shows_progress(args: argparse.Namespace) -> bool:
    """Whether a subcommand draws its progress bar on stderr (the ``progress=True`` of the
    Python API): not with ``--quiet``, nor when stderr is no terminal (a log file)."""
    return not args.quiet and sys.stderr.isatty()
