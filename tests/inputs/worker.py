"""Runs corpus cases by id, one JSON line per case on stdout, for tests/inputs/test_corpus.py.

The test process talks to this worker over pipes and kills it when a case takes longer than its timeout, so a
hang fails that case instead of blocking the suite; an input that ends the process (``exit()`` run as code)
shows as a worker that died. Run in a scratch directory: payloads that would run code write corpus.CANARY
there, and the worker reports whether the file appeared.
"""

import json
import os
import sys
import traceback
import warnings

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import corpus  # noqa: E402


def main():
    warnings.simplefilter("ignore")
    table = {c.id: c for c in corpus.cases()}
    print(json.dumps({"ready": len(table)}), flush=True)
    for line in sys.stdin:
        cid = line.strip()
        if not cid:
            continue
        case = table[cid]
        out = {"id": cid}
        try:
            value = case.run()
        except BaseException as exc:  # noqa: BLE001 - SystemExit from exit() run as code must be seen too
            out.update(outcome="raised", cls=type(exc).__name__, module=type(exc).__module__,
                       message=str(exc)[:6000])
            if not type(exc).__module__.startswith("kinbook"):
                out["traceback"] = traceback.format_exc()[-3000:]
        else:
            out.update(outcome="returned", value=repr(value)[:2000])
            if case.expect == "cli":
                out["status"], out["stderr"] = value
            elif case.check is not None:
                try:
                    out["checked"] = bool(case.check(value))
                except Exception as exc:  # noqa: BLE001
                    out["checked"] = False
                    out["check_error"] = repr(exc)
        out["canary"] = os.path.exists(corpus.CANARY)
        if out["canary"]:
            os.remove(corpus.CANARY)
        print(json.dumps(out), flush=True)


if __name__ == "__main__":
    main()
