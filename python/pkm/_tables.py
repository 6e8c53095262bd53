"""CSV tables of the library's file-based runs as dicts of numpy columns (used by the compiled module).

A column whose fields are all integers becomes an integer array, one whose fields are all numbers (empty
fields: NaN) a float64 array, any other a str array; so a table with text columns (pose ids, statuses)
keeps them, which numpy.genfromtxt with one dtype would turn into NaN.
"""

import csv

import numpy


def _column(values):
    try:
        return numpy.array([int(v) for v in values])
    except (ValueError, OverflowError):
        pass
    try:
        return numpy.array([float(v) if v != "" else numpy.nan for v in values], dtype=numpy.float64)
    except ValueError:
        return numpy.array(values, dtype=str)


def read_csv_table(path):
    """The columns of the CSV at `path` by their header names (lines starting with '#' skipped)."""
    with open(path, newline="", encoding="utf-8") as file:
        rows = [row for row in csv.reader(line for line in file if not line.startswith("#"))]
    header, body = rows[0], rows[1:]
    return {name: _column([row[k] if k < len(row) else "" for row in body]) for k, name in enumerate(header)}
