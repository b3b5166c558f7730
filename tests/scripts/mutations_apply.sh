#!/usr/bin/env bash
# Every mutation of scripts/mutations.ini still applies: its `from` text occurs exactly once in its file, so
# that scripts/mutate.sh (run by hand, minutes a mutation) does not find the list gone stale. Run by ctest
# from the project's root.
set -euo pipefail
/usr/bin/python3 - <<'PY'
import configparser, sys
c = configparser.ConfigParser(interpolation=None)
c.optionxform = str
c.read("scripts/mutations.ini")
stale = []
for name in c.sections():
    m = c[name]
    try:
        n = open(m["file"]).read().count(m["from"])
    except OSError:
        n = -1
    if n != 1:
        stale.append("%s: %s %s" % (name, m["file"], "is missing" if n < 0 else "holds its 'from' %d times" % n))
for s in stale:
    print("stale mutation " + s)
print("%d mutations, %d stale" % (len(c.sections()), len(stale)))
sys.exit(1 if stale else 0)
PY
