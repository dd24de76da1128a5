"""A test script's checks: each prints `ok` or `FAIL` with what it checked, and the script ends with the
plain closing line 'N passed, N failed' and exit status 0 or 1."""


class Checklist:
    def __init__(self):
        self.passed = 0
        self.failed = []

    def check(self, ok, what):
        print(("ok   " if ok else "FAIL ") + what, flush=True)
        if ok:
            self.passed += 1
        else:
            self.failed.append(what)
        return ok

    def finish(self):
        print(f"{self.passed} passed, {len(self.failed)} failed")
        return 1 if self.failed else 0
