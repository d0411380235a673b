"""What every command-line program in scripts/ shares: its main guarded so that bad input ends in one line
naming the file (and line) or the option, exit 2, never a traceback; and argparse types for numbers that
refuse NaN, infinities, unparsable text and values out of range, naming the option."""
import argparse
import csv
import math
import os
import sys

import oitbench
from oitbench.results import ResultsError

USAGE_ERROR = 2
INTERRUPTED = 130


class InputError(Exception):
    """A bad input that is not a CSV file: an option's value, an output path, a folder's contents.
    The message names the option or the file."""


def run(main, argv=None):
    """sys.exit(cli.run(main)): main's exit status; ResultsError, InputError and unreadable or unwritable
    files print `PROG: MESSAGE` and give 2, a third-party module this Python cannot import gives 1 (naming the
    module, its Debian package and the interpreter), Ctrl-C gives 130, without a traceback."""
    prog = os.path.basename(sys.argv[0]) or "oitbench"
    try:
        return main() if argv is None else main(argv)
    except (ResultsError, InputError) as e:
        print(f"{prog}: {e}", file=sys.stderr)
        return USAGE_ERROR
    except OSError as e:
        where = e.filename if e.filename is not None else "?"
        print(f"{prog}: {where}: {e.strerror or e}", file=sys.stderr)
        return USAGE_ERROR
    except (UnicodeError, csv.Error) as e:
        print(f"{prog}: unreadable input ({e})", file=sys.stderr)
        return USAGE_ERROR
    except ModuleNotFoundError as e:
        print(oitbench.missing_module_message(e), file=sys.stderr)
        return oitbench.FAILED
    except KeyboardInterrupt:
        print(f"{prog}: interrupted", file=sys.stderr)
        return INTERRUPTED


def _bound(x):
    return f"{x:g}" if isinstance(x, float) else str(x)


def number(kind=float, low=None, high=None, low_open=False, high_open=False):
    """An argparse `type=` for a finite number of `kind` (int or float) within [low, high] (an open end
    with low_open/high_open). argparse names the option in its message and exits 2."""

    def parse(text):
        what = "an integer" if kind is int else "a number"
        try:
            x = kind(text)
        except (TypeError, ValueError):
            raise argparse.ArgumentTypeError(f"'{text}' is not {what}") from None
        if kind is float and not math.isfinite(x):
            raise argparse.ArgumentTypeError(f"'{text}' is not a finite number")
        if low is not None and (x < low or (low_open and x == low)):
            raise argparse.ArgumentTypeError(f"{text} is out of range: must be {'>' if low_open else '>='} "
                                             f"{_bound(low)}")
        if high is not None and (x > high or (high_open and x == high)):
            raise argparse.ArgumentTypeError(f"{text} is out of range: must be {'<' if high_open else '<='} "
                                             f"{_bound(high)}")
        return x

    parse.__name__ = "integer" if kind is int else "number"
    return parse


def positive(kind=float):
    """A finite number > 0 (an int >= 1)."""
    return number(kind, low=1) if kind is int else number(kind, low=0.0, low_open=True)


def non_negative(kind=float):
    return number(kind, low=0)


def fraction(low_open=False, high_open=False):
    """A finite number in [0, 1]."""
    return number(float, 0.0, 1.0, low_open, high_open)
