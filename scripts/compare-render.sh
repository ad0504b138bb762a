#!/usr/bin/env bash
# Renders the same .tsp under a set of option lines with two tspplay binaries and reports whether
# every PNG is byte-identical and frames.json agrees apart from timings (a refactor's check that
# `render` output did not change).
#   compare-render.sh OLD_TSPPLAY NEW_TSPPLAY FILE.tsp [OUT_DIR]   (option lines on stdin)
set -euo pipefail
old=$1 new=$2 tsp=$3 out=${4:-$(mktemp -d)}
mkdir -p "$out"
i=0 status=0
while IFS= read -r opts; do
  i=$((i + 1))
  rm -rf "$out/o$i" "$out/n$i"
  # shellcheck disable=SC2086  # the option line is split into words on purpose
  "$old" render "$tsp" --size 160x120 $opts -o "$out/o$i" > /dev/null
  # shellcheck disable=SC2086
  "$new" render "$tsp" --size 160x120 $opts -o "$out/n$i" > /dev/null
  same=yes
  for f in "$out/o$i"/*.png; do cmp -s "$f" "$out/n$i/$(basename "$f")" || same=no; done
  json=$(python3 - "$out/o$i/frames.json" "$out/n$i/frames.json" <<'PY'
import json, sys
def strip(x):
    if isinstance(x, dict):
        return {k: strip(v) for k, v in x.items()
                if not k.endswith('_ms') and k not in ('ms', 'renderer', 'cost') and 'rss' not in k
                and 'ram' not in k}
    if isinstance(x, list):
        return [strip(v) for v in x]
    return x
o, n = (strip(json.load(open(p))) for p in sys.argv[1:3])
print('same' if all(o[k] == n.get(k) for k in o) else 'differs',
      'added:' + ','.join(sorted(set(n) - set(o))))
PY
)
  echo "[$opts] pngs identical: $same; frames.json: $json"
  [ "$same" = yes ] && [[ $json == same* ]] || status=1
done
exit $status
