#!/bin/bash
# The Slurm route for real (ctest study_slurm): a single-node Slurm on localhost (munged with a
# generated key, slurmctld and slurmd with a generated slurm.conf, all under WORK and on ports of
# their own), a study of two stage-1 jobs (render + reference) and its compare, submitted with the
# script `bounce sweep --emit slurm` writes. Torn down on exit. Exit 77 (skipped) only when
# slurm-wlm cannot start here, and never when CI=true.
#
# With a third argument, a study file, the same Slurm then runs that whole study too (not under
# ctest: docs/studies.md's demo study through Slurm is `tests/study/slurm_test.sh build/src/app/bounce
# /tmp/slurm scripts/demo-study.json`), and its records are checked against a local run: the same jobs
# and statuses; the jobs whose metrics differ are listed.
#
# usage: slurm_test.sh BOUNCE WORK [STUDY]
set -u
BOUNCE=$1
WORK=$2
STUDY=${3:-}

skip() {
  if [ "${CI:-}" = "true" ]; then echo "FAIL: $* (CI=true: the Slurm test must run)"; exit 1; fi
  echo "skipped: $*"
  exit 77
}
logs() { for f in "$WORK"/log/*.log "$WORK"/out/logs/*.log; do [ -f "$f" ] && { echo "== $f"; tail -n 15 "$f"; }; done; }
fail() { echo "FAIL: $*"; logs; exit 1; }

for b in munged munge slurmctld slurmd sbatch squeue sinfo; do
  command -v "$b" >/dev/null || skip "$b is not installed (scripts/install-deps.sh installs munge and slurm-wlm)"
done
# slurmd starts job steps as their user, which needs root; CI and the development machine are root.
[ "$(id -u)" = 0 ] || skip "slurmd needs root to launch jobs"

rm -rf "$WORK"
mkdir -p "$WORK"/munge "$WORK"/state "$WORK"/spool "$WORK"/log
chmod 755 "$WORK"/munge  # clients need to reach the socket
cleanup() {
  if [ -n "${SLURM_CONF:-}" ]; then scancel --quiet -u root 2>/dev/null || true; fi
  local pids=""
  for p in "$WORK"/slurmd.pid "$WORK"/slurmctld.pid "$WORK"/munge/munged.pid; do
    [ -f "$p" ] && pids="$pids $(cat "$p")"
  done
  for pid in $pids; do kill "$pid" 2>/dev/null; done
  # The daemons save state before exiting: wait (up to 10 s) so the next run finds them gone.
  for _ in $(seq 100); do
    alive=""
    for pid in $pids; do kill -0 "$pid" 2>/dev/null && alive="$alive $pid"; done
    [ -z "$alive" ] && return 0
    sleep 0.1
  done
  for pid in $alive; do kill -9 "$pid" 2>/dev/null; done
  return 0
}
trap cleanup EXIT

# munge: a fresh key, its own socket; nothing of the machine's munge is used.
head -c 1024 /dev/urandom > "$WORK"/munge/munge.key
chmod 400 "$WORK"/munge/munge.key
SOCKET="$WORK"/munge/munge.socket
munged --force --socket="$SOCKET" --key-file="$WORK"/munge/munge.key --log-file="$WORK"/log/munged.log \
  --pid-file="$WORK"/munge/munged.pid --seed-file="$WORK"/munge/munged.seed || skip "munged does not start: $(tail -n 1 "$WORK"/log/munged.log 2>/dev/null)"
for _ in $(seq 50); do [ -S "$SOCKET" ] && break; sleep 0.1; done
munge -S "$SOCKET" -n | unmunge -S "$SOCKET" >/dev/null || skip "munge credentials do not round-trip"

# Ports from the process id, so two builds on one machine do not collide (range 20000-59999).
PORT=$((20000 + ($$ % 20000) * 2))
HOST=$(hostname -s)
cat > "$WORK"/slurm.conf <<EOF
ClusterName=bouncetest
SlurmctldHost=$HOST(127.0.0.1)
SlurmctldPort=$PORT
SlurmdPort=$((PORT + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$SOCKET
CredType=cred/munge
StateSaveLocation=$WORK/state
SlurmdSpoolDir=$WORK/spool
SlurmctldPidFile=$WORK/slurmctld.pid
SlurmdPidFile=$WORK/slurmd.pid
SlurmctldLogFile=$WORK/log/slurmctld.log
SlurmdLogFile=$WORK/log/slurmd.log
# No cgroups: containers and CI runners rarely delegate them.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
MpiDefault=none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
NodeName=$HOST NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=bounce Nodes=$HOST Default=YES MaxTime=INFINITE State=UP OverSubscribe=YES
EOF
export SLURM_CONF="$WORK"/slurm.conf
slurmctld -f "$SLURM_CONF" || skip "slurmctld does not start: $(tail -n 1 "$WORK"/log/slurmctld.log 2>/dev/null)"
slurmd -f "$SLURM_CONF" -N "$HOST" || skip "slurmd does not start: $(tail -n 1 "$WORK"/log/slurmd.log 2>/dev/null)"
state=""
for _ in $(seq 60); do
  state=$(sinfo -h -o %T 2>/dev/null | head -n 1)
  [ "$state" = "idle" ] && break
  sleep 0.5
done
[ "$state" = "idle" ] || skip "the node did not come up (state '$state'): $(tail -n 1 "$WORK"/log/slurmd.log 2>/dev/null)"
echo "ok: single-node Slurm up on $HOST, ports $PORT/$((PORT + 1))"

cat > "$WORK"/two.json <<'EOF'
{"name": "two", "size": "16x16", "scenes": ["cornell-box"], "techniques": ["direct"], "reference": {"spp": 4}}
EOF
"$BOUNCE" sweep "$WORK"/two.json --out "$WORK"/out --emit slurm || fail "--emit slurm"
[ "$(wc -l < "$WORK"/out/jobs/stage1.txt)" = 2 ] || fail "stage 1 should list 2 jobs"
grep -q -- "--array=1-2" "$WORK"/out/jobs/slurm-stage1.sbatch || fail "stage 1 is a 2-task array"
ids=$("$WORK"/out/jobs/submit-slurm.sh) || fail "submit-slurm.sh: $ids"
echo "ok: submitted $(echo $ids)"
for _ in $(seq 240); do
  [ -z "$(squeue -h -o %i 2>/dev/null)" ] && break
  sleep 0.5
done
[ -z "$(squeue -h -o %i)" ] || fail "jobs still queued after 120 s: $(squeue)"

for job in render/cornell-box/direct/default reference/cornell-box/b0/f0000 compare/cornell-box/direct/default; do
  grep -q '"status": "ok"' "$WORK"/out/$job/record.json 2>/dev/null || fail "$job has no finished record"
done
[ -f "$WORK"/out/logs/slurm-stage1-1.log ] && [ -f "$WORK"/out/logs/slurm-stage1-2.log ] && [ -f "$WORK"/out/logs/slurm-stage2-1.log ] \
  || fail "the array tasks' logs are missing (did Slurm run them?)"
echo "ok: the two array tasks and the dependent compare ran under Slurm"

# Same records as a local run of the same study.
"$BOUNCE" sweep "$WORK"/two.json --out "$WORK"/local > /dev/null || fail "local run"
/usr/bin/python3 - "$WORK" <<'EOF' || fail "Slurm and local records differ"
import json, sys
w = sys.argv[1]
def load(root):
    with open(f"{root}/compare/cornell-box/direct/default/record.json") as f:
        return json.load(f)
a, b = load(f"{w}/out"), load(f"{w}/local")
assert a["spec"] == b["spec"] and a["metrics"] == b["metrics"], (a["metrics"], b["metrics"])
print("ok: Slurm and local compare records agree")
EOF
[ -n "$STUDY" ] || exit 0

# The given study, all of it, through the same Slurm, then locally.
"$BOUNCE" sweep "$STUDY" --out "$WORK"/study-slurm --emit slurm || fail "--emit slurm $STUDY"
start=$(date +%s)
ids=$("$WORK"/study-slurm/jobs/submit-slurm.sh) || fail "submit-slurm.sh: $ids"
echo "ok: submitted $STUDY as $(echo $ids)"
for _ in $(seq 7200); do  # up to an hour
  [ -z "$(squeue -h -o %i 2>/dev/null)" ] && break
  sleep 0.5
done
[ -z "$(squeue -h -o %i)" ] || fail "$STUDY: jobs still queued after an hour"
echo "ok: $STUDY ran under Slurm in $(( $(date +%s) - start )) s"
"$BOUNCE" sweep "$STUDY" --out "$WORK"/study-local --jobs 2 > /dev/null || fail "local run of $STUDY"
/usr/bin/python3 - "$WORK" <<'EOF' || fail "Slurm and local records of the study differ"
import json, os, sys
from collections import Counter
w = sys.argv[1]
def records(root):
    out = {}
    for folder, _dirs, files in os.walk(root):
        if "record.json" in files:
            with open(os.path.join(folder, "record.json")) as f:
                r = json.load(f)
            out[r["job"]] = r
    return out
a, b = records(f"{w}/study-slurm"), records(f"{w}/study-local")
assert sorted(a) == sorted(b), f"jobs differ: {sorted(set(a) ^ set(b))[:5]}"
assert {j: r["status"] for j, r in a.items()} == {j: r["status"] for j, r in b.items()}, "statuses differ"
keys = ("metrics", "leak", "flicker", "convergence")
differ = [j for j in a if any(a[j].get(k) != b[j].get(k) for k in keys)]
print(f"ok: {len(a)} records, statuses {dict(Counter(r['status'] for r in a.values()))} as in the local run; "
      f"metrics differ in {len(differ)}: {differ}")
EOF
exit 0
