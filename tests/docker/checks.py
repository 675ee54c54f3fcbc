"""What the docker checks share: each check counted, its failure kept, and the report."""
import sys

errors = []
checks = 0


def check(ok, message):
    global checks
    checks += 1
    if not ok:
        errors.append(message)


def read(path):
    with open(path) as f:
        return f.read()


def report(what=""):
    """Prints each failure and the count; the exit code."""
    for e in errors:
        print(f"docker.compose: FAIL: {e}", file=sys.stderr)
    print(f"docker.compose: {checks - len(errors)} of {checks} checks passed" + (f" ({what})" if what else ""))
    return 1 if errors else 0
