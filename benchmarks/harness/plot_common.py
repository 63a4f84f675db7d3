"""What gplan-bench's plotting scripts share (plot_bench.py, plot_error_time.py,
plot_broad_phase.py): reading a CSV that gplan-bench wrote, file names for figures,
writing a figure whole or not at all, and the scripts' main.

gplan-bench runs each script embedded in its binary with this module ahead of it
(benchmarks/CMakeLists.txt embeds both); run on its own, a script imports this file
from beside it.
"""
import csv
import math
import os
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
from matplotlib import pyplot  # noqa: E402  (after the backend is chosen)


class BadCsv(Exception):
    """The CSV is not one gplan-bench wrote; the message names the file and line."""


def parse_time(text, allow_empty=True):
    """A time in seconds (finite, not negative); None for an empty field where allowed."""
    if text == "" and allow_empty:
        return None
    try:
        value = float(text)
    except ValueError:
        raise BadCsv("'%s' is no number" % text)
    if not math.isfinite(value) or value < 0:
        raise BadCsv("'%s' is no time in seconds (finite, not negative)" % text)
    return value


def parse_count(text, allow_empty=True):
    """A count (decimal digits); None for an empty field where allowed."""
    if text == "" and allow_empty:
        return None
    if not text.isdigit() or len(text) > 18:
        raise BadCsv("'%s' is no count" % text)
    return int(text)


def field(row, column, parse):
    """parse(row[column]), a BadCsv from it naming the column."""
    try:
        return parse(row[column])
    except BadCsv as error:
        raise BadCsv("column %s: %s" % (column, error))


def require(row, columns):
    """BadCsv when one of `columns` is empty."""
    for column in columns:
        if row[column] == "":
            raise BadCsv("column %s is empty" % column)


def read_csv(path, headers, kind, parse):
    """The records of the CSV at `path`, each row (a dict of the header's columns) made
    a record by parse(row), which raises BadCsv (without the file and line) for a row
    gplan-bench would not write. headers: the headers accepted (the current one first);
    kind: what the CSV is, for messages ("a gplan-bench CSV")."""
    try:
        with open(path, newline="", encoding="utf-8", errors="replace") as file:
            reader = csv.reader(file, strict=True)
            records = []
            try:
                header = next(reader, None)
                if header not in headers:
                    raise BadCsv("%s:1: not %s (the header differs from gplan's: %s)"
                                 % (path, kind, ",".join(headers[0])))
                for fields in reader:
                    if fields == []:
                        continue
                    line = reader.line_num
                    if len(fields) != len(header):
                        raise BadCsv("%s:%d: %d fields, not %d"
                                     % (path, line, len(fields), len(header)))
                    try:
                        records.append(parse(dict(zip(header, fields))))
                    except BadCsv as error:
                        raise BadCsv("%s:%d: %s" % (path, line, error))
            except csv.Error as error:
                raise BadCsv("%s:%d: %s" % (path, reader.line_num, error))
    except OSError as error:
        raise BadCsv("%s: cannot be read (%s)" % (path, error.strerror or error))
    return records


def file_stem(name):
    """`name` as a file name: characters other than letters, digits, '.', '-' and '_' as
    '_', never a hidden or relative name."""
    stem = "".join(c if c.isascii() and (c.isalnum() or c in "._-") else "_" for c in name)
    return "_" + stem if stem.startswith(".") or stem == "" else stem


def check_file_names(figures):
    """BadCsv when two of `figures` ((what, name) pairs: scenes, tables, the overview,
    experiments' folders) would be written to the same file, before anything is drawn."""
    taken = {}
    for what, name in figures:
        stem = file_stem(name)
        if stem in taken:
            raise BadCsv("%s '%s' and %s '%s' would both be written to %s; rename one"
                         % (taken[stem] + (what, name, stem)))
        taken[stem] = (what, name)


def save(figure, out_dir, stem):
    """Writes figure as out_dir/stem.png and .svg, each whole or not at all (a temporary
    file renamed over it, keeping the mode of a file it replaces; a symbolic link is
    written through)."""
    for extension, metadata in (("png", {"Software": None}),
                                ("svg", {"Date": None, "Creator": None})):
        path = os.path.realpath(os.path.join(out_dir, stem + "." + extension))
        handle, temporary = tempfile.mkstemp(prefix="." + stem + ".", suffix=".part",
                                             dir=os.path.dirname(path))
        try:
            with os.fdopen(handle, "wb") as file:
                figure.savefig(file, format=extension, metadata=metadata)
            if os.path.exists(path):
                os.chmod(temporary, os.stat(path).st_mode & 0o7777)
            else:
                umask = os.umask(0)
                os.umask(umask)
                os.chmod(temporary, 0o666 & ~umask)
            os.replace(temporary, path)
        except BaseException:
            os.unlink(temporary)
            raise
    pyplot.close(figure)


def main(argv, script, salt, read, draw):
    """`script CSV OUT_DIR`: draw(read(CSV), OUT_DIR) with matplotlib's defaults (the same
    figures whatever the user's matplotlibrc says; SVGs hashed with `salt`, so that the
    output is deterministic). Exit 0 drawn, 1 an output could not be written, 2 the CSV
    is not one gplan-bench wrote (or bad usage)."""
    if len(argv) != 3:
        print("usage: %s CSV OUT_DIR" % script, file=sys.stderr)
        return 2
    matplotlib.rcdefaults()
    matplotlib.rcParams["svg.hashsalt"] = salt
    matplotlib.rcParams["path.simplify"] = True
    try:
        draw(read(argv[1]), argv[2])
    except BadCsv as error:
        print("%s: %s" % (script, error), file=sys.stderr)
        return 2
    except OSError as error:
        print("%s: %s: cannot be written (%s)"
              % (script, error.filename or argv[2], error.strerror or error), file=sys.stderr)
        return 1
    return 0
