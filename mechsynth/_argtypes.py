"""Value parsers shared by the CLI commands (argparse ``type=`` callables).

>>> whole("3"), positive("2"), finite("-1.5"), seconds("0.5"), workers("1"), number_range("-90..90")
(3, 2, -1.5, 0.5, 1, (-90.0, 90.0))
"""

from __future__ import annotations

import argparse
import math
import os

from mechbase import RangeSyntax, parse_range

__all__ = ["whole", "positive", "real", "finite", "seconds", "inches", "workers", "number_range", "picture_file",
           "output_file", "output_folder", "where_conditions", "PICTURE_FORMATS", "GivenOnce", "GIVEN",
           "YesOrNo", "add_row", "chain_text", "LINKAGE_FILE_USES"]

#: what a picture may be written as
PICTURE_FORMATS = (".png", ".pdf", ".svg")


class GivenOnce(argparse.Action):
    """Base of every option of the command line that holds one value: given a second time (or with its
    negation) it is refused in one sentence, where argparse would silently keep the last; options that
    collect values (``action="append"``) stay repeatable.  :class:`mechsynth._parser._Parser` makes argparse's
    own single-value actions of this kind; the values given are remembered on the namespace, under
    :data:`GIVEN`, until the root parser removes them.

    >>> parser = argparse.ArgumentParser(exit_on_error=False)
    >>> _ = parser.add_argument("--links", action=type("Once", (GivenOnce, argparse._StoreAction), {}))
    >>> parser.parse_args(["--links", "8", "--links", "9"])
    Traceback (most recent call last):
    argparse.ArgumentError: --links is given twice: give it once
    """

    def __call__(self, parser, namespace, values, option_string=None):
        if option_string is not None:  # (a positional argument is read once)
            given = namespace.__dict__.setdefault(GIVEN, {})
            if self.dest in given:
                action, earlier = given[self.dest]
                if action is self and not (isinstance(self, argparse.BooleanOptionalAction) and earlier != option_string):
                    raise argparse.ArgumentError(None, f"{option_string} is given twice: give it once")
                both = sorted([earlier, option_string], key=lambda o: o.startswith("--no-"))
                raise argparse.ArgumentError(None, f"{both[0]} and {both[1]} contradict each other")
            given[self.dest] = (self, option_string)
        super().__call__(parser, namespace, values, option_string)


#: the namespace's attribute that holds the single-value options given so far
GIVEN = "_given_once"


class YesOrNo(GivenOnce, argparse.BooleanOptionalAction):
    """``--x`` / ``--no-x``, refusing both on one command line (argparse would keep the last), or either twice.

    >>> parser = argparse.ArgumentParser(exit_on_error=False)
    >>> _ = parser.add_argument("--labels", action=YesOrNo)
    >>> parser.parse_args(["--no-labels"]).labels
    False
    >>> parser.parse_args(["--labels", "--no-labels"])
    Traceback (most recent call last):
    argparse.ArgumentError: --labels and --no-labels contradict each other
    """


def _read(text: str, number, what: str):
    """``number(text)`` (``int`` or ``float``), or argparse's error naming ``what``."""
    try:
        return number(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected {what}, not {text!r}") from None


def whole(text: str) -> int:
    """A whole number (negative values are left to the command's own check)."""
    return _read(text, int, "a whole number")


def positive(text: str) -> int:
    """A whole number ≥ 1 (workers, columns, limits)."""
    value = whole(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"expected a whole number ≥ 1, not {value}")
    return value


#: what each command that reads a chain's text can do with a linkage file given there instead: the command
#: that reads it (and for a .json file, the chain read from its text, where the command in hand can use it)
LINKAGE_FILE_USES = {
    "analyze": ("'mechsynth identify {file}' gives its chain's code, W, sub-chains and name",
                "mechsynth analyze \"$(cat {file})\""),
    "chains": ("'mechsynth identify {file}' gives its chain's id and row in its code's listing",
               "mechsynth chains --chain \"$(cat {file})\""),
    "mechanisms": ("'mechsynth identify {file}' gives its mechanism's row in its code's listing (its frame too)",
                   "mechsynth mechanisms --chain \"$(cat {file})\""),
    "draw": ("draw takes it as its first argument and draws it to scale: 'mechsynth draw {file} --out FILE'", None),
    "move": ("move takes it as its first argument: 'mechsynth move {file}'", None),
}


def chain_text(command: str):
    """The argparse type of a chain given as text to ``command`` (a joint list or a JSON row), refusing in one
    sentence a word that names a file, where the chain's reader would say it cannot read a joint or a code of
    that name: a linkage file is named with what ``command`` can do with it (:data:`LINKAGE_FILE_USES`), any
    other file with ``identify``, which reads the chains of a file.

    >>> chain_text("analyze")("0-1 1-2 2-3 3-0")
    '0-1 1-2 2-3 3-0'
    >>> chain_text("move")("models/motion_four_bar.toml")
    Traceback (most recent call last):
    argparse.ArgumentTypeError: models/motion_four_bar.toml is a linkage file, and move --chain reads a chain as it is written (a joint list '0-1 1-2 …' or a JSON row): move takes it as its first argument: 'mechsynth move models/motion_four_bar.toml'
    >>> chain_text("analyze")("a = 1\\nb = 2")
    Traceback (most recent call last):
    argparse.ArgumentTypeError: the text given is 2 lines, beginning 'a = 1' (a file's text?), and analyze reads a chain written on one line ('0-1 1-2 …') or a JSON row: 'mechsynth identify FILE' reads the chains of a file
    """
    use, text_use = LINKAGE_FILE_USES[command]
    where = command if command == "analyze" else f"{command} --chain"

    def chain(text: str) -> str:
        word = text.strip()
        if "\n" in word and not word.startswith(("{", "[")):  # a file's text, as "$(cat L.toml)" gives it
            raise argparse.ArgumentTypeError(
                f"the text given is {len(word.splitlines())} lines, beginning {word.splitlines()[0][:40]!r} (a file's "
                f"text?), and {where} reads a chain written on one line ('0-1 1-2 …') or a JSON row: "
                "'mechsynth identify FILE' reads the chains of a file")
        if not word or any(c.isspace() for c in word) or not os.path.isfile(word):
            return text
        read_here = f"{where} reads a chain as it is written (a joint list '0-1 1-2 …' or a JSON row)"
        if not _is_linkage_file(word):
            raise argparse.ArgumentTypeError(f"{word} is a file, and {read_here}: 'mechsynth identify {word}' reads "
                                             "the chains of a file")
        as_text = f", or '{text_use.format(file=word)}' reads its chain" if text_use and word.lower().endswith(
            ".json") else ""
        raise argparse.ArgumentTypeError(f"{word} is a linkage file, and {read_here}: {use.format(file=word)}{as_text}")

    return chain


def _is_linkage_file(path: str) -> bool:
    """Whether ``path`` holds one linkage (as move and dimension --save write it)."""
    if not path.lower().endswith((".json", ".toml")):
        return False
    from synth import SynthesisError
    from synth.motion import read_linkage

    try:
        read_linkage(path)
    except SynthesisError:  # no linkage, or rows of several (the caller names identify)
        return False
    return True


def add_row(parser, also: str = "") -> None:
    """``--row K``: which row of an atlas search's rows (``dimension --db … --format json`` or ``jsonl``) is
    the linkage a command reads (:func:`synth.motion.read_linkage`); ``also`` ends its help with what else it
    picks in this command.

    >>> p = argparse.ArgumentParser(); add_row(p); p.parse_args(["--row", "2"]).row
    2
    """
    parser.add_argument("--row", type=positive, metavar="K",
                        help="with a file of an atlas search's rows (dimension --db … --format json or jsonl): the "
                             "linkage of row K (1 = the best, as the table ranks them)" + also)


def real(text: str, what: str = "a number") -> float:
    """A real number, ``inf`` and ``nan`` included (what else it must be is the caller's check); ``what``
    names the value in the error: ``expected a number of seconds, not 'x'``.

    >>> real("1e-3"), real("-inf")
    (0.001, -inf)
    """
    return _read(text, float, what)


def finite(text: str) -> float:
    """A finite real number (a bound, an angle, a ratio: its range is the command's check)."""
    value = real(text)
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"expected a finite number, not {text!r}")
    return value


def seconds(text: str) -> float:
    """A time in seconds > 0."""
    value = real(text, "a number of seconds")
    if not value > 0:
        raise argparse.ArgumentTypeError(f"expected a positive number of seconds, not {text!r}")
    return value


def inches(text: str) -> float:
    """A drawing's edge in inches, 0.5 … 30 (larger pictures would only fill memory)."""
    value = real(text, "a size in inches")
    if not 0.5 <= value <= 30:
        raise argparse.ArgumentTypeError(f"expected a size of 0.5 to 30 inches, not {text}")
    return value


def workers(text: str) -> int:
    """Local worker processes: 1 … the number of cores (more only slow each other down and fill memory)."""
    value = positive(text)
    cores = os.cpu_count() or 1
    if value > cores:
        raise argparse.ArgumentTypeError(
            f"{value} workers is more than the {cores} cores of this machine (extra processes only wait for a core)")
    return value


def number_range(text: str) -> tuple[float, float]:
    """``"A..B"`` of real numbers (negative ones and ``inf`` allowed; whether low < high is the command's check).

    >>> number_range("0..inf")
    (0.0, inf)
    """
    try:
        pair = parse_range(text, float, open_high=False) if ".." in text else None
    except RangeSyntax:
        pair = None
    if pair is None or any(math.isnan(v) for v in pair):
        raise argparse.ArgumentTypeError(f"expected a range low..high of numbers (e.g. 20..160), not {text!r}")
    return pair


def output_file(text: str, suffixes: tuple[str, ...], what: str) -> str:
    """An output file whose name ends in one of ``suffixes`` and that can be written, checked before any
    work is done (a probe file is made and removed where none exists); ``what`` names what goes in it.

    >>> import os, tempfile; path = os.path.join(tempfile.mkdtemp(), "a.svg")
    >>> output_file(path, (".png", ".svg"), "the picture") == path, os.path.exists(path)
    (True, False)
    """
    if os.path.splitext(text)[1].lower() not in suffixes:
        def either(words):
            return words[0] if len(words) == 1 else ", ".join(words[:-1]) + " or " + words[-1]

        raise argparse.ArgumentTypeError(f"{what} is written as {either([x[1:].upper() for x in suffixes])}: end the "
                                         f"file name in {either(list(suffixes))}, not {text!r}")
    if os.path.isdir(text):
        raise argparse.ArgumentTypeError(f"{text} is a directory, not a file to write {what} to")
    if os.path.exists(text):
        if not os.access(text, os.W_OK):
            raise argparse.ArgumentTypeError(f"cannot write {what} to {text}: permission denied")
        return text
    try:
        with open(text, "x"):
            pass
        os.remove(text)
    except OSError as exc:
        raise argparse.ArgumentTypeError(f"cannot write {what} to {text}: {exc.strerror or exc}") from None
    return text


def picture_file(text: str) -> str:
    """A figure's file name ending in .png, .pdf or .svg that can be written (:func:`output_file`)."""
    return output_file(text, PICTURE_FORMATS, "the figure")


def output_folder(text: str) -> str:
    """A folder that files can be written into: it exists or can be made, and a file can be made in it
    (checked before any work is done: a probe file is made and removed, and a folder made for the probe
    is removed again).

    >>> import tempfile; output_folder(tempfile.gettempdir()) == tempfile.gettempdir()
    True
    """
    import tempfile

    if not text.strip():
        raise argparse.ArgumentTypeError("expected the name of a folder, not ''")
    if os.path.exists(text) and not os.path.isdir(text):
        raise argparse.ArgumentTypeError(f"{text} is a file; give a directory for the files to write")
    made = not os.path.exists(text)
    try:
        if made:
            os.mkdir(text)
        with tempfile.TemporaryFile(dir=text):
            pass
    except OSError as exc:
        raise argparse.ArgumentTypeError(f"cannot write files into {text}: {exc.strerror or exc}") from None
    finally:
        if made and os.path.isdir(text):
            os.rmdir(text)
    return text


def where_conditions(groups: list[list[str]]) -> list[str]:
    """The conditions of repeated ``--where`` options (``nargs="+"``): ``--where n3 '>=' 2`` and
    ``--where n3>=2`` are the same condition.

    >>> where_conditions([["n3", ">=", "2"], ["W=1"]])
    ['n3>=2', 'W=1']
    """
    return ["".join(words) for words in groups]


def mechanism_of(chain, frame: int, input_joint: str | None):
    """The mechanism named by ``--frame F`` and ``--input F-L`` on ``chain`` (the input joint of the
    frame and one moving link; without ``--input``, the mechanism's own choice).

    >>> from synth import Chain
    >>> mechanism_of(Chain.parse("0-1 1-2 2-3 3-0"), 0, "1-0").input_link
    1
    """
    from synth import InvalidOption, Mechanism

    if not 0 <= frame < chain.links:
        raise InvalidOption(f"--frame {frame} is not a link of the chain (links 0 … {chain.links - 1})")
    driven = None
    if input_joint is not None:
        links = chain.joints[chain.joint_index(input_joint, "--input")]
        if len(links) != 2 or frame not in links:
            raise InvalidOption(f"--input {input_joint} must be a joint of the frame (link {frame}) and one "
                                f"moving link, written like {frame}-1")
        driven = links[0] if links[1] == frame else links[1]
    return Mechanism(chain, frame, driven)
