"""What the run checkers share: collecting the checks that fail, reading a
CSV file's rows, and the verdict with the exit status."""
import csv

failures = []


def check(condition, message):
    """Record @p message if @p condition is false; return the condition."""
    if not condition:
        failures.append(message)
    return condition


def rows(path):
    """The rows of a one-header-line CSV file as dicts of strings."""
    with open(path) as f:
        return list(csv.DictReader(f))


def verdict(passed="all checks passed", shown=30):
    """Print the failed checks (the first @p shown) or @p passed; the exit
    status: 1 if any check failed, else 0."""
    if failures:
        print(f"{len(failures)} check(s) failed:")
        for f in failures[:shown]:
            print("  ", f)
        return 1
    print(passed)
    return 0
