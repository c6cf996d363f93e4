#!/usr/bin/env bash
# A run on a disk that fills, on a tmpfs of 8 MiB mounted in a user and
# mount namespace of its own (no root needed where the kernel allows
# unprivileged namespaces; skipped with exit 77 and the reason where not):
#  - a full disk at the start refuses the run (exit 65) and writes nothing;
#  - a disk that fills mid-run stops it with exit 73 and the reason, leaves
#    history.csv ending in a whole row, no temporary file, and frames that
#    `verify` passes;
#  - once space is freed, `resume` finishes the run from its checkpoint.
# Usage: full_disk.sh RUNOUT
set -u
runout=$1

if [[ -z "${RUNOUT_FULL_DISK_NS:-}" ]]; then
  if ! unshare --user --map-root-user --mount true 2>/dev/null; then
    echo "skipped: no unprivileged user and mount namespaces here (unshare failed), so no tmpfs to fill"
    exit 77
  fi
  RUNOUT_FULL_DISK_NS=1 exec unshare --user --map-root-user --mount "$0" "$@"
fi

work=$(mktemp -d)
disk=$work/disk
trap 'umount "$disk" 2>/dev/null; rm -rf "$work"' EXIT
mkdir "$disk"
if ! mount -t tmpfs -o size=8m tmpfs "$disk"; then
  echo "skipped: cannot mount a tmpfs in the namespace"
  exit 77
fi

failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# The small block of tests/cli_runner.hpp, 30 s with a frame every 0.5 s.
cat >"$work/scene.toml" <<'EOF'
[scene]
name = "small"
[grid]
cell_size = 0.5
min = [0.0, 0.0]
max = [20.0, 5.0]
[boundary]
bottom = "slip"
[time]
end = 30.0
output_interval = 0.5
[gravity]
slope_angle = 10.0
[[material]]
name = "clay"
density = 600.0
youngs_modulus = 1.0e5
poisson_ratio = 0.3
[[body]]
name = "block"
material = "clay"
type = "rectangle"
min = [1.0, 0.0]
max = [5.0, 2.0]
EOF

fill_disk() { dd if=/dev/zero of="$disk/fill" bs=64k 2>/dev/null; }
out=$disk/out

# Full at the start: refused before anything is written.
fill_disk
"$runout" run "$work/scene.toml" -q -t 1 -o "$out" >"$work/start.log" 2>&1
code=$?
[[ $code == 65 ]] || fail "a full disk at the start: exit $code, expected 65: $(cat "$work/start.log")"
grep -q "free space on that disk" "$work/start.log" || fail "no remedy: $(cat "$work/start.log")"
[[ ! -e $out ]] || fail "the refused run created $out"
rm -f "$disk/fill"

# Full in the middle of the run.
"$runout" run "$work/scene.toml" -q -t 1 --checkpoint-every 1 -o "$out" >"$work/mid.log" 2>&1 &
run=$!
for _ in $(seq 600); do
  [[ -e $out/frame_00002.vtu ]] && break
  sleep 0.05
done
fill_disk
wait "$run"
code=$?
[[ $code == 73 ]] || fail "a disk full mid-run: exit $code, expected 73: $(cat "$work/mid.log")"
grep -q "No space left on device" "$work/mid.log" || fail "no reason given: $(cat "$work/mid.log")"
[[ $(tail -c 1 "$out/history.csv" | od -An -c | tr -d ' ') == '\n' ]] ||
  fail "history.csv ends in a torn row: $(tail -c 80 "$out/history.csv")"
ls -A "$out" | grep -q '\.tmp\.' && fail "temporaries left: $(ls -A "$out" | grep '\.tmp\.')"
"$runout" verify "$out" >"$work/verify.log" 2>&1 || fail "verify after the full disk: $(cat "$work/verify.log")"

# Space freed: the resume finishes the run, every frame whole.
rm -f "$disk/fill"
"$runout" resume -q -t 1 "$out" >"$work/resume.log" 2>&1 || fail "resume: $(cat "$work/resume.log")"
"$runout" verify "$out" >"$work/verify.log" 2>&1 || fail "verify after the resume: $(cat "$work/verify.log")"
frames=$(ls "$out" | grep -c '^frame_.*\.vtu$')
[[ $frames == 61 ]] || fail "$frames frames after the resume, expected 61"

[[ $failures == 0 ]] && echo "full disk: every probe held"
exit $((failures > 0))
