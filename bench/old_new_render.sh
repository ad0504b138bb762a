#!/bin/bash
# Alternates an old (OLD=, e.g. a build of c5640ba) and a new tspplay (NEW=) on one fixed configuration; prints median ms of pass 2.

OLD=$(realpath "${OLD:?path of the old tspplay}"); NEW=$(realpath "${NEW:-build/tspplay}")
# DATA_DIR holds shock.tsp and shock_tf.json (the demo's dataset and map).
cd "${DATA_DIR:-.}"
for shade in on off; do
  for round in 1 2 3; do
    for who in old new; do
      B=$OLD; [ $who = new ] && B=$NEW
      rm -rf ab_out; $B render shock.tsp --tf shock_tf.json --steps 4:7 --size 640x480 --shade $shade --reuse off --passes 2 -o ab_out > /dev/null 2>&1
      python3 -c "
import json,statistics;j=json.load(open('ab_out/frames.json')); fr=j['frames'] if 'frames' in j else j
print('$shade $round $who', round(statistics.median([f['ms'] for f in fr if f.get('pass',1)==2]),1), fr[-1].get('caster','gl'))"
    done
  done
done
