#!/bin/bash
# Issue 23 (reliability, round two): every numbered defect and "Also:" item that the CLI shows, as
# exact-behaviour checks. Usage: round_two.sh BIN_DIR [ID...] (BIN_DIR holds vibrissa and vibrissa-full).
# Prints PASS/FAIL per check; exits 1 if any check fails. Each check takes well under a second.
set -u
BIN="$1/vibrissa"
shift
ONLY=" $* "
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
FAILED=0
OUT="$TMP/out" ERR="$TMP/err"

# run CMD...: runs with a 60 s limit; sets RC, and $OUT/$ERR hold stdout/stderr.
run() { timeout 60 "$@" >"$OUT" 2>"$ERR"; RC=$?; }
# check ID DESCRIPTION CONDITION...: the condition is a shell test evaluated after run.
check() {
  local id="$1" what="$2"
  shift 2
  if [[ "$ONLY" != "  " && "$ONLY" != *" $id "* ]]; then return; fi
  if "$@"; then
    echo "PASS $id: $what"
  else
    echo "FAIL $id: $what (exit $RC; stderr: $(head -c 400 "$ERR" | tr '\n' ' '))"
    FAILED=1
  fi
}
clean_error() {  # exit 1, one "vibrissa: error:" message, nothing a library says on its own
  [[ $RC -eq 1 ]] && grep -q "^vibrissa: error: " "$ERR" &&
    ! grep -qE "internal error|bad_alloc|json.exception|HDF5-DIAG|HDF5: |terminate|Segmentation|At Most|[0-9]{40}" "$ERR"
}
stderr_has() { grep -qE "$1" "$ERR"; }

CASE='{"whisker": {"length": 0.03, "curvature": 20.0}, "load": {"mode": "point", "point": [0.02, 0.004, 0.001]}}'
case_with() { echo "{\"whisker\": $1, \"load\": $2}" >"$TMP/case.json"; }
POINT_LOAD='{"mode": "point", "point": [0.02, 0.004, 0.001]}'

# 1. -o to a character device or a FIFO writes to it, never replaces it; a symlink's target is replaced.
echo "$CASE" >"$TMP/ok.json"
run "$BIN" solve "$TMP/ok.json" -o /dev/null
check D1 "solve -o /dev/null: written to, still a character device" bash -c "[[ $RC -eq 0 && -c /dev/null ]]"
mkfifo "$TMP/fifo"
(cat "$TMP/fifo" >"$TMP/fifo.out" &)
run "$BIN" solve "$TMP/ok.json" -o "$TMP/fifo"
sleep 0.2
check D1b "solve -o FIFO: the reader gets the result, the FIFO stays" bash -c "[[ $RC -eq 0 && -p $TMP/fifo ]] && grep -q status $TMP/fifo.out"
echo old >"$TMP/target.json"
ln -s target.json "$TMP/link.json"
run "$BIN" solve "$TMP/ok.json" -o "$TMP/link.json"
check D1c "solve -o SYMLINK: the link stays, its target holds the result" bash -c "[[ $RC -eq 0 && -L $TMP/link.json ]] && grep -q status $TMP/target.json"

# 2. One line of invalid UTF-8 is a bad line like any other: the batch goes on, with -o too.
{ echo "$CASE"; printf '{"whisker": {"length": 0.03, "scheme": "\xff\xfe"}, "load": 1}\n'; echo "$CASE"; } >"$TMP/batch.jsonl"
run "$BIN" solve --jsonl "$TMP/batch.jsonl" -o "$TMP/batch.out"
check D2 "jsonl: invalid UTF-8 line reported, later lines solved" \
  bash -c "[[ $RC -eq 1 ]] && [[ \$(wc -l <'$TMP/batch.out') -eq 3 ]] && sed -n 2p '$TMP/batch.out' | grep -q '\"line\":2' && sed -n 3p '$TMP/batch.out' | grep -q '\"status\"'"
run "$BIN" solve --jsonl "$TMP/batch.jsonl"
check D2b "jsonl to stdout: three lines, valid UTF-8" \
  bash -c "[[ \$(wc -l <'$OUT') -eq 3 ]] && iconv -f UTF-8 -t UTF-8 '$OUT' >/dev/null"

# Property (batch continuation): 300 lines, valid cases mutated at random bytes (invalid UTF-8, NUL, overflowing
# numbers, truncation), seeded: one output line per non-blank input line, each valid UTF-8 JSON, in order.
python3 - "$TMP/fuzz.jsonl" <<'PY'
import random, sys
rng = random.Random(23)
base = [b'{"whisker": {"length": 0.03, "curvature": 20.0}, "load": {"mode": "point", "point": [0.02, 0.004, 0.001]}}',
        b'{"whisker": {"length": 0.03, "cubic": [5, 15], "links": 40}, "load": {"mode": "force", "force": 1e-4, "arc_length": 0.02}}',
        b'{"whisker": {"points": [[0,0,0],[0.01,0.001,0],[0.02,0.004,0]]}, "load": {"mode": "dead_load", "force": [0, 1e-4, 0], "arc_length": 0.02}}']
junk = [b"\xff", b"\xc3", b"\xed\xa0\x80", b"\x00", b"1e400", b"-1e-310", b"nan", b"[]", b'"', b"\\u0000", b"{", b"}"]
with open(sys.argv[1], "wb") as out:
    for k in range(300):
        line = bytearray(rng.choice(base))
        for _ in range(rng.randrange(0, 3)):
            at = rng.randrange(len(line))
            if rng.random() < 0.5:
                line[at:at] = rng.choice(junk)
            else:
                del line[at:at + rng.randrange(1, 8)]
        out.write(bytes(line).replace(b"\n", b" ") + b"\n")
PY
run "$BIN" solve --jsonl "$TMP/fuzz.jsonl"
check P2 "jsonl property: one valid JSON result per line, in order, for 300 mutated lines" \
  python3 -c "
import json, sys
lines = [l for l in open('$TMP/fuzz.jsonl', 'rb').read().split(b'\n') if l.strip(b' \t\r')]
out = open('$OUT', 'rb').read().decode('utf-8').splitlines()
assert len(out) == len(lines), (len(out), len(lines))
for k, text in enumerate(out):
    r = json.loads(text)
    assert ('error' in r and r['line'] == k + 1) or 'status' in r, text[:200]
assert $RC in (0, 1)
"

# 3. reconstruct --nodes bounded before reading or allocating.
run "$BIN" reconstruct --top "$TMP/none.csv" --front "$TMP/none.csv" --calibration "$TMP/none.json" -o "$TMP/r.h5" --nodes 1000000000
check D3 "reconstruct --nodes 1e9: error naming nodes and the limit" clean_error
check D3 "" stderr_has "nodes must be in \[2, 99999\], got 1e\+09"
run "$BIN" reconstruct --top "$TMP/none.csv" --front "$TMP/none.csv" --calibration "$TMP/none.json" -o "$TMP/r.h5" --nodes 100000
check D3b "reconstruct --nodes 100000 (100,001 points) refused" stderr_has "nodes must be in"

# 4. Subnormal numbers rejected with the field.
for c in '{"length": 0.03, "curvature": 20.0, "base_stiffness": 1e-310}|base_stiffness' \
         '{"length": 0.03, "curvature": 20.0, "base_stiffness": 5e-324}|base_stiffness'; do
  case_with "${c%|*}" "$POINT_LOAD"; run "$BIN" solve "$TMP/case.json"
  check D4 "subnormal ${c#*|}" bash -c "$(declare -f clean_error); RC=$RC ERR=$ERR clean_error && grep -q '${c#*|}' $ERR"
done
case_with '{"length": 0.03, "curvature": 20.0}' '{"mode": "point", "point": [0.02, 0.004, 1e-310]}'
run "$BIN" solve "$TMP/case.json"
check D4b "subnormal point coordinate" bash -c "$(declare -f clean_error); RC=$RC ERR=$ERR clean_error && grep -q 'load.point' $ERR"
case_with '{"length": 0.03, "curvature": 20.0}' '{"mode": "point", "point": [0.02, 0.004, 0.001], "arc_length_hint": 1e-310}'
run "$BIN" solve "$TMP/case.json"
check D4c "subnormal arc_length_hint" bash -c "$(declare -f clean_error); RC=$RC ERR=$ERR clean_error && grep -q 'arc_length_hint' $ERR"

# 5. --peg-mm / --edge-mm repeatable.
run "$BIN" reconstruct --top "$TMP/none.csv" --front "$TMP/none.csv" --calibration "$TMP/none.json" -o "$TMP/r.h5" \
  --peg-mm 1 2 3 --peg-mm 4 5 6 --edge-mm 1 2 3 0 0 1 --edge-mm 4 5 6 0 1 0
check D5 "--peg-mm and --edge-mm repeated are accepted (the run fails later, on the missing files)" \
  bash -c "[[ $RC -eq 1 ]] && ! grep -qiE 'At Most|required' $ERR && grep -q 'none' $ERR"

# 6. trial --mu nan is an error.
for flag in --mu --mu-eq7; do
  run "$BIN" trial "$0" $flag nan --no-figures
  check D6 "trial $flag nan refused" bash -c "$(declare -f clean_error); RC=$RC ERR=$ERR clean_error && grep -q 'must be finite and >= 0, got nan' $ERR"
done

# 7. Empty lists are errors like lists of one.
for c in '{"length": 0.03, "curvature": 20.0, "radii": []}|radii' '{"length": 0.03, "curvature": 20.0, "youngs_modulus": []}|youngs_modulus'; do
  case_with "${c%|*}" "$POINT_LOAD"; run "$BIN" solve "$TMP/case.json"
  check D7 "empty ${c#*|}" bash -c "$(declare -f clean_error); RC=$RC ERR=$ERR clean_error && grep -q '${c#*|}.*at least 2 values, got 0' $ERR"
done

# 8. Unwritable output directory and a full disk: a clean error, no HDF5 noise, no crash.
echo x >"$TMP/a_file"
run "$BIN" array --out "$TMP/a_file/sub" --no-figures
check D8 "array into an unwritable place" clean_error
run bash -c "ulimit -f 100; trap '' XFSZ; exec '$BIN' synth '$TMP/big.h5' --duration 3.3 --shapes"
check D8b "synth on a full disk (ulimit -f 100)" clean_error
run bash -c "ulimit -f 100; trap '' XFSZ; exec '$BIN' array --out '$TMP/arr' --no-figures --csv"
check D8c "array on a full disk (ulimit -f 100)" clean_error

# 9. synth never writes what trial refuses; no bare bad_alloc.
run "$BIN" synth "$TMP/s.h5" --duration 1000.001
check D9 "synth --duration 1000.001 refused (> 1,000,000 frames)" bash -c "$(declare -f clean_error); RC=$RC ERR=$ERR clean_error && grep -q '1000001 frames' $ERR && [[ ! -e $TMP/s.h5 ]]"
run "$BIN" synth "$TMP/s.h5" --duration 1e9
check D9b "synth --duration 1e9 refused" clean_error
run "$BIN" synth "$TMP/s.h5" --duration nan
check D9c "synth --duration nan refused" clean_error

# 11. Messages.
case_with '{"length": 0.03, "cubic": [1e308, 5], "scheme": "paper"}' "$POINT_LOAD"
run "$BIN" solve "$TMP/case.json"
check D11a "paper scheme with an overflowing cubic names the field" bash -c "$(declare -f clean_error); RC=$RC ERR=$ERR clean_error && grep -q 'whisker.curvature/cubic' $ERR"
run "$BIN" reconstruct --top x --front x --calibration x -o "$TMP/r.h5" --nodes 0
check D11b "nodes 0: 'got 0'" stderr_has "got 0$"
run "$BIN" reconstruct --top x --front x --calibration x -o "$TMP/r.h5" --contact-threshold-um -1
check D11c "contact threshold -1 um: readable value" stderr_has "got -1e-06"
run "$BIN" solve --bogus
check D11d "unknown flag exits 1" bash -c "[[ $RC -eq 1 ]]"
run "$BIN" trial "$0" --filter-order 3
check D11d "invalid flag value exits 1" bash -c "[[ $RC -eq 1 ]]"
run "$BIN" reconstruct --top x --front x --calibration x -o "$TMP/r.h5" --peg-mm 1 2
check D11d "too few flag values exit 1" bash -c "[[ $RC -eq 1 ]]"
run "$BIN" trial "$0" --cutoff inf --no-figures
check D11e "--cutoff inf: short message" bash -c "[[ $RC -eq 1 ]] && [[ \$(wc -c <$ERR) -lt 200 ]] && grep -q 'got inf' $ERR"
run "$BIN" trial "$0" --cutoff 1e308 --no-figures
check D11e "--cutoff 1e308: no 309-digit number" bash -c "! grep -qE '[0-9]{40}' $ERR"
printf '{"whisker": {"length": 0.03,\n "curvature": 1e400}, "load": {"mode": "point", "point": [0.02, 0.004, 0.001]}}\n' >"$TMP/case.json"
run "$BIN" solve "$TMP/case.json"
check D11f "number overflow: line and column" bash -c "$(declare -f clean_error); RC=$RC ERR=$ERR clean_error && grep -q 'line 2, column 15' $ERR"

# Property (bounds on every option, uniform validation): every numeric flag of trial, synth, reconstruct and
# array given nan, inf, a subnormal, -1, 1e300 or text ends with status 0 or 1 within the time
# limit, and an error is one clean message (no internal error, bad_alloc, CLI11 code, HDF5 noise, 40 digits).
if [[ "$ONLY" == "  " || "$ONLY" == *" P3 "* ]]; then
  p3_failed=0 p3_runs=0
  declare -A FIXED=(
    [trial]="$0 --no-figures --out $TMP/trial_out"
    [synth]="$TMP/p3.h5"
    [reconstruct]="--top $TMP/none.csv --front $TMP/none.csv --calibration $TMP/none.json -o $TMP/p3r.h5"
    [array]="$TMP/tiny_array.json --out $TMP/p3a --no-figures")
  # A small scene (5 frames, 20 links, one pitch): a flag value that is accepted runs in a few milliseconds.
  "$BIN" array --print-default-config | python3 -c "
import json, sys
c = json.load(sys.stdin)
c['time']['frames'] = 5; c['solver']['links'] = 20; c['output']['render_count'] = 2
json.dump(c, open('$TMP/tiny_array.json', 'w'))"
  for sub in trial synth reconstruct array; do
    flags=$("$BIN" $sub --help | grep -oE '^ +--[a-z0-9-]+ (FLOAT|INT|UINT|X Y Z)' | awk '{print $1}')
    for flag in $flags; do
      for value in nan inf 1e-310 -1 1e300 x; do
        args=("$value")
        [[ $flag == --peg-mm ]] && args=("$value" 1 1)
        [[ $flag == --edge-mm ]] && args=("$value" 1 1 0 0 1)
        run "$BIN" $sub ${FIXED[$sub]} "$flag" "${args[@]}"
        p3_runs=$((p3_runs + 1))
        if ! { [[ $RC -eq 0 ]] || clean_error; } || grep -qE '[0-9]{40}' "$ERR"; then
          echo "  P3: $sub $flag $value -> exit $RC: $(head -c 300 "$ERR" | tr '\n' ' ')"
          p3_failed=1
        fi
      done
    done
  done
  RC=$p3_failed
  check P3 "every numeric flag x {nan, inf, 1e-310, -1, 1e300, x}: exit 0/1, clean messages ($p3_runs runs)" \
    test $p3_failed -eq 0
fi

# Also: paper scheme + points + links is an error, never ignored.
case_with '{"points": [[0, 0, 0], [0.01, 0.001, 0], [0.02, 0.004, 0]], "scheme": "paper", "links": 100}' "$POINT_LOAD"
run "$BIN" solve "$TMP/case.json"
check A5 "paper scheme + points + links refused" bash -c "$(declare -f clean_error); RC=$RC ERR=$ERR clean_error && grep -q 'whisker.links' $ERR"
# Also: hairpin and self-crossing points are errors naming the segments.
case_with '{"points": [[0, 0, 0], [0.01, 0, 0], [0.02, 0, 0], [0.012, 0.0001, 0], [0.005, 0.0002, 0]]}' "$POINT_LOAD"
run "$BIN" solve "$TMP/case.json"
check A2 "hairpin points refused naming the segments" bash -c "[[ $RC -eq 1 ]] && grep -q 'segments' $ERR"
case_with '{"points": [[0, 0, 0], [0.02, 0, 0], [0.02, 0.01, 0], [0.01, 0.01, 0], [0.01, -0.01, 0]]}' "$POINT_LOAD"
run "$BIN" solve "$TMP/case.json"
check A2b "self-crossing points refused naming the segments" bash -c "[[ $RC -eq 1 ]] && grep -q 'segments 0 and 3' $ERR"
# Also: a not_converged dead load reports the residual of the state it returns.
case_with '{"length": 0.03, "curvature": 20}' '{"mode": "dead_load", "force": [0, 1, 0], "arc_length": 0.0299}'
run "$BIN" solve "$TMP/case.json"
check A3 "dead load 1 N: the reported residual belongs to the returned force" \
  /usr/bin/python3 -c "
import json, sys
r = json.load(open('$OUT'))
st = r['status'] if isinstance(r['status'], str) else r['status'].get('name')
print(st, r.get('residual'), r.get('force_W', r.get('force')), file=sys.stderr)
sys.exit(0 if st == 'converged' or r.get('residual', 0) > 1e-6 else 1)"

# Also (this session's hunt): the length given is the whisker's arc length, so a load at s = L is on it.
case_with '{"length": 0.03, "curvature": 40}' '{"mode": "force", "force": 1e-4, "arc_length": 0.03}'
run "$BIN" solve "$TMP/case.json"
check L1 "length 0.03, curvature 40: a load at s = 0.03 is on the whisker" bash -c "[[ $RC -eq 0 ]] && grep -q '\"converged\"' $OUT"
# An empty output path is an error, not standard output or the default folder.
echo "$CASE" >"$TMP/ok.json"
run "$BIN" solve "$TMP/ok.json" -o ""
check O1 "solve -o '' refused" bash -c "$(declare -f clean_error); RC=$RC ERR=$ERR clean_error && grep -q 'empty path' $ERR"
run "$BIN" synth ""
check O2 "synth '' refused" bash -c "$(declare -f clean_error); RC=$RC ERR=$ERR clean_error && grep -q 'OUT: must name a file or folder, got an empty path' $ERR"
# A mesh file that crashes assimp (a face index of -1) is an error naming object.file, not a crash.
printf 'ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n0.01 -0.01 -0.01\n0.03 -0.01 -0.01\n0.01 0.01 -0.01\n0.01 -0.01 0.01\n3 0 1 2\n3 0 1 -1\n3 0 2 3\n3 1 2 3\n' >"$TMP/bad.ply"
case_with '{"length": 0.03, "curvature": 20}' "{\"mode\": \"object\", \"object\": {\"type\": \"mesh\", \"file\": \"$TMP/bad.ply\"}}"
run "$BIN" solve "$TMP/case.json"
check M1 "a PLY that crashes assimp is an error naming object.file" bash -c "$(declare -f clean_error); RC=$RC ERR=$ERR clean_error && grep -q 'object.file: cannot read mesh' $ERR && ! grep -q ai_assert $ERR"

exit $FAILED
