#!/bin/sh
# CTest cli.interrupt_keeps_rows: `pradis run` stopped by SIGINT exits with 130
# and keeps the rows computed so far in <stem>.csv (no <stem>.csv.part left).
# Usage: test_interrupt.sh PRADIS_EXECUTABLE SCRATCH_DIR
set -u
exe=$1
dir=$2
rm -rf "$dir"
mkdir -p "$dir"
cat > "$dir/long.prd" <<'MODEL'
$FRAGMENT
#STRUCTURE
  Body 'MASS (1; 1)
  Spring 'SPRING (0 1; 100)
  Push 'F (1; 1)
#OUTPUT
  Position 'X (1; 1)
$RUN
  Calc 'SHTERM (END=1E6, OUT=1, SMAX=1E-3)
$END
MODEL
"$exe" run "$dir/long.prd" -o "$dir" -q &
pid=$!
# The run takes hours: wait until its first rows have reached the temporary file.
n=0
while [ ! -s "$dir/long.csv.part" ] || [ "$(wc -l < "$dir/long.csv.part")" -lt 3 ]; do
  n=$((n + 1))
  if [ $n -gt 600 ]; then
    kill -9 $pid
    echo "FAILED: no rows in $dir/long.csv.part"
    exit 1
  fi
  sleep 0.1
done
kill -INT $pid
wait $pid
rc=$?
if [ $rc -ne 130 ]; then echo "FAILED: exit status $rc, expected 130"; exit 1; fi
if [ -e "$dir/long.csv.part" ]; then echo "FAILED: $dir/long.csv.part left behind"; exit 1; fi
rows=$(wc -l < "$dir/long.csv")
if [ "$rows" -lt 3 ]; then echo "FAILED: $dir/long.csv has $rows lines"; exit 1; fi
head -1 "$dir/long.csv"
echo "interrupted run kept $rows lines"
