#!/usr/bin/env python3
# Checks that two CSV files differ only in how their numbers are spelled: every field the
# same text, or two numbers that parse to the same double, the new one no longer.
#   scripts/same_csv_numbers.py OLD.csv NEW.csv [OLD2.csv NEW2.csv ...]
# (Used when results.csv moved from %.17g to the shortest exact text.)
import csv, sys
def rows(p): return list(csv.reader(open(p, newline='')))
bad = 0; changed = 0
for old_p, new_p in zip(sys.argv[1::2], sys.argv[2::2]):
    a, b = rows(old_p), rows(new_p)
    assert len(a) == len(b), (old_p, len(a), len(b))
    for ra, rb in zip(a, b):
        assert len(ra) == len(rb)
        for fa, fb in zip(ra, rb):
            if fa == fb: continue
            changed += 1
            try:
                if float(fa) != float(fb) or len(fb) > len(fa): bad += 1; print("DIFF", fa, fb)
            except ValueError:
                bad += 1; print("TEXT", fa, fb)
print("changed fields", changed, "bad", bad)
sys.exit(1 if bad else 0)
