#!/usr/bin/env bash
# The pipeline on a real SLURM: profiles/slurm against a private single-node SLURM with accounting.
#
#   bash tests/cluster/run.sh                 # the test (as root on Debian 12; CI runs it from .ci/run)
#   bash tests/cluster/run.sh -- CMD ARGS...  # the same private SLURM, then CMD instead of the test
#
# Phases (each one's wall time is printed):
#   apt      munge slurmctld slurmd slurm-client slurmdbd mariadb-server (--no-install-recommends)
#   daemons  slurm.conf/slurmdbd.conf in a private directory; MariaDB, munged (unless one already
#            answers), slurmdbd, slurmctld and slurmd on the loopback, detached; cluster, account
#            and user registered with sacctmgr
#   run      in scratch clones of this repository's HEAD (tests/cluster/check.py says what counts):
#            1. local reference   snakemake --cores 2 --configfile config/test.yaml
#            2. failing job       snakemake --profile profiles/slurm with a record that does not
#                                 exist (config/test.yaml + bad.yaml): only its job can tell; the
#                                 run must fail and name the job's log
#            3. fixed rerun       snakemake --profile profiles/slurm --configfile config/test.yaml
#            4. check             every compute job ran in a SLURM job that sacct lists COMPLETED;
#                                 the datasets equal those of step 1 variable by variable
# Every daemon it started is stopped by its pid file on exit (trap), whatever happened.
# Without root or apt-get it says so and exits 0.  Each snakemake runs under `timeout -s KILL`
# (the SLURM executor can wait forever when status checks fail).
# Environment: ISOSLIDE_SLURM_DIR (private directory; default: a new /tmp/isoslide-slurm.*, removed
# on success), ISOSLIDE_SLURM_TIMEOUT (seconds per snakemake run; default 1800: the run took 530 s on
# one machine of this kind and processors differ about twofold in speed).
set -euo pipefail

REPO=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
PACKAGES=(munge slurmctld slurmd slurm-client slurmdbd mariadb-server)
RUN_TIMEOUT=${ISOSLIDE_SLURM_TIMEOUT:-1800}
CLUSTER=isoslide
ACCOUNT=isoslide
PARTITION=main          # the partition named in profiles/slurm/config.yaml
BAD_RECORD=No_such_record_1994

say() { printf '[cluster %(%H:%M:%S)T] %s\n' -1 "$*"; }
now() { date +%s.%N; }
took() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }'; }

if [ "$(id -u)" != 0 ] || ! command -v apt-get >/dev/null 2>&1; then
    say "SKIPPED: a private SLURM needs root and apt-get (Debian); this machine has" \
        "uid $(id -u) and apt-get $(command -v apt-get >/dev/null 2>&1 && echo present || echo absent)"
    exit 0
fi
for port in 3306 6817 6818 6819; do
    if (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null; then
        say "FAILED: port $port on 127.0.0.1 is in use (a MariaDB or SLURM already runs here);" \
            "stop it first, this test starts its own"
        exit 1
    fi
done

# ---------------------------------------------------------------------------------------- apt
t_apt=$(now)
missing=()
for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    say "apt: installing ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq >/dev/null
    apt-get install -y -qq --no-install-recommends "${PACKAGES[@]}" >/dev/null
fi
APT_S=$(took "$t_apt")
say "phase apt: ${APT_S} s"

# ------------------------------------------------------------------------------------ daemons
t_daemons=$(now)
W=${ISOSLIDE_SLURM_DIR:-$(mktemp -d /tmp/isoslide-slurm.XXXXXX)}
mkdir -p "$W"/{etc,run,log,state,spool,db}
chmod 755 "$W"
PIDFILES=()   # in start order; stopped in reverse
OK=0
LINKED=0      # 1 once /etc/slurm/slurm.conf is our symlink

stop_daemons() {
    local i pidfile pid n
    for ((i = ${#PIDFILES[@]} - 1; i >= 0; i--)); do
        pidfile=${PIDFILES[i]}
        [ -s "$pidfile" ] || continue
        pid=$(cat "$pidfile")
        kill -0 "$pid" 2>/dev/null || continue
        kill -TERM "$pid" 2>/dev/null || true
        for ((n = 0; n < 100; n++)); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
        if kill -0 "$pid" 2>/dev/null; then
            say "$(basename "$pidfile" .pid) (pid $pid) ignored SIGTERM for 10 s: SIGKILL"
            kill -KILL "$pid" 2>/dev/null || true
        fi
        say "stopped $(basename "$pidfile" .pid) (pid $pid)"
    done
}
on_exit() {
    local rc=$?
    trap - EXIT INT TERM
    stop_daemons
    if [ "$LINKED" = 1 ] && [ -L /etc/slurm/slurm.conf ]; then rm -f /etc/slurm/slurm.conf; fi
    if [ "$rc" = 0 ] && [ "$OK" = 1 ] && [ -z "${ISOSLIDE_SLURM_DIR:-}" ]; then
        rm -rf "$W"
    elif [ "$rc" != 0 ]; then
        for f in "$W"/log/*.log; do
            [ -s "$f" ] || continue
            echo "----- last lines of $f"; tail -n 15 "$f"
        done
        say "kept $W for inspection"
    fi
    exit "$rc"
}
trap on_exit EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

wait_for() {  # wait_for SECONDS WHAT COMMAND...: poll COMMAND every 0.2 s
    local limit=$1 what=$2 n
    shift 2
    for ((n = 0; n < limit * 5; n++)); do
        "$@" >/dev/null 2>&1 && return 0
        sleep 0.2
    done
    say "FAILED: $what did not come up within $limit s"
    return 1
}

HOST=$(hostname -s)
NODE_LINE=$(slurmd -C | head -n 1)   # NodeName=<host> CPUs=... RealMemory=...
export SLURM_CONF="$W/etc/slurm.conf"

# MariaDB, private: its own data directory, socket and pid file; TCP on the loopback only.
mariadb-install-db --no-defaults --user=root --datadir="$W/db" --auth-root-authentication-method=normal \
    --skip-test-db >"$W/log/mariadb-install.log" 2>&1
PIDFILES+=("$W/run/mariadb.pid")
setsid mariadbd --no-defaults --user=root --datadir="$W/db" --socket="$W/run/mariadb.sock" \
    --pid-file="$W/run/mariadb.pid" --bind-address=127.0.0.1 --port=3306 \
    --log-error="$W/log/mariadb.log" </dev/null >/dev/null 2>&1 &
wait_for 60 MariaDB mariadb-admin --socket="$W/run/mariadb.sock" -u root ping
mariadb --socket="$W/run/mariadb.sock" -u root -e "
    CREATE USER 'slurm'@'127.0.0.1' IDENTIFIED BY 'isoslide';
    GRANT ALL ON slurm_acct_db.* TO 'slurm'@'127.0.0.1';"

# munged: the system's if one answers, else ours (as the munge user, key from the munge package).
if munge -n 2>/dev/null | unmunge >/dev/null 2>&1; then
    say "munged: using the one already running"
else
    install -d -o munge -g munge -m 0755 /run/munge "$W/run/munge" "$W/log/munge"
    [ -s /etc/munge/munge.key ] || runuser -u munge -- mungekey --create
    PIDFILES+=("$W/run/munge/munged.pid")
    setsid runuser -u munge -- munged --pid-file="$W/run/munge/munged.pid" \
        --log-file="$W/log/munge/munged.log" </dev/null >/dev/null 2>&1
    wait_for 20 munged sh -c 'munge -n | unmunge'
fi

cat >"$W/etc/slurmdbd.conf" <<EOF
AuthType=auth/munge
DbdAddr=127.0.0.1
DbdHost=localhost
DbdPort=6819
SlurmUser=root
LogFile=$W/log/slurmdbd.log
PidFile=$W/run/slurmdbd.pid
StorageType=accounting_storage/mysql
StorageHost=127.0.0.1
StoragePort=3306
StorageUser=slurm
StoragePass=isoslide
StorageLoc=slurm_acct_db
EOF
chmod 600 "$W/etc/slurmdbd.conf"

cat >"$W/etc/slurm.conf" <<EOF
ClusterName=$CLUSTER
SlurmctldHost=$HOST(127.0.0.1)
SlurmUser=root
SlurmctldPort=6817
SlurmdPort=6818
AuthType=auth/munge
StateSaveLocation=$W/state
SlurmdSpoolDir=$W/spool
SlurmctldPidFile=$W/run/slurmctld.pid
SlurmdPidFile=$W/run/slurmd.pid
SlurmctldLogFile=$W/log/slurmctld.log
SlurmdLogFile=$W/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
MinJobAge=300
MailProg=/bin/true
AccountingStorageType=accounting_storage/slurmdbd
AccountingStorageHost=127.0.0.1
AccountingStoragePort=6819
AccountingStoreFlags=job_comment
JobAcctGatherType=jobacct_gather/linux
JobAcctGatherFrequency=10
$NODE_LINE NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=$PARTITION Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF

# The plugin's job step removes every SLURM_* variable, SLURM_CONF included, before its srun: the
# configuration must be where SLURM looks by default.  A symlink to ours, removed on exit.
if [ -e /etc/slurm/slurm.conf ] || [ -L /etc/slurm/slurm.conf ]; then
    say "FAILED: /etc/slurm/slurm.conf exists (a SLURM is configured here); this test writes its own"
    exit 1
fi
mkdir -p /etc/slurm
ln -s "$W/etc/slurm.conf" /etc/slurm/slurm.conf
LINKED=1

PIDFILES+=("$W/run/slurmdbd.pid")
setsid slurmdbd </dev/null >/dev/null 2>&1
wait_for 60 slurmdbd sacctmgr -n list cluster
sacctmgr -i add cluster "$CLUSTER" >/dev/null
sacctmgr -i add account "$ACCOUNT" Cluster="$CLUSTER" Description=isoslide Organization=isoslide >/dev/null
sacctmgr -i add user root Account="$ACCOUNT" DefaultAccount="$ACCOUNT" >/dev/null

PIDFILES+=("$W/run/slurmctld.pid")
setsid slurmctld </dev/null >/dev/null 2>&1
wait_for 60 slurmctld scontrol ping
PIDFILES+=("$W/run/slurmd.pid")
setsid slurmd </dev/null >/dev/null 2>&1
wait_for 60 "node $HOST (idle)" sh -c "sinfo -h -N -o %T | grep -qx idle"
DAEMONS_S=$(took "$t_daemons")
say "phase daemons: ${DAEMONS_S} s ($(sinfo -h -N -o '%N %c CPUs %m MB %T'), partition $PARTITION)"

if [ "${1:-}" = "--" ]; then
    shift
    say "running: $*"
    "$@" &
    wait $!   # in the background, so that SIGTERM reaches the trap at once
    OK=1
    exit 0
fi

# ---------------------------------------------------------------------------------------- run
t_run=$(now)
git clone -q "$REPO" "$W/local"
git clone -q "$REPO" "$W/cluster"
say "scratch clones of $(git -C "$REPO" rev-parse --short HEAD) in $W/local and $W/cluster"

smk() {  # smk DIR LOG ARGS...: snakemake in DIR on the clone's own package, killed after the timeout
    local dir=$1 log=$2
    shift 2
    (cd "$dir" && PYTHONPATH="$dir/src" timeout -s KILL "$RUN_TIMEOUT" \
        python -m snakemake "$@" >"$log" 2>&1)
}
# the profile as a user runs it; the test keeps SLURM's logs (check.py reads them) and polls often
SLURM_ARGS=(--profile profiles/slurm --slurm-keep-successful-logs --slurm-init-seconds-before-status-checks 2
            --seconds-between-status-checks 3 --max-status-checks-per-second 1)

t=$(now)
smk "$W/local" "$W/log/run-local.log" --cores 2 --configfile config/test.yaml \
    || { say "FAILED: local reference run, see $W/log/run-local.log"; tail -n 40 "$W/log/run-local.log"; exit 1; }
say "1. local reference run (--cores 2): $(took "$t") s"

cat >"$W/bad.yaml" <<EOF
records:
  names: [Northridge_1994_PAC-175, $BAD_RECORD]
EOF
t=$(now)
rc=0
smk "$W/cluster" "$W/log/run-failing.log" "${SLURM_ARGS[@]}" --configfile config/test.yaml "$W/bad.yaml" || rc=$?
say "2. run with a failing job: exit $rc after $(took "$t") s"
if [ "$rc" = 0 ] || [ "$rc" = 137 ]; then
    say "FAILED: the run with record $BAD_RECORD should fail by itself (exit $rc; 137 = killed by the timeout)"
    tail -n 40 "$W/log/run-failing.log"
    exit 1
fi
python "$REPO/tests/cluster/check.py" failure --cluster "$W/cluster" --log "$W/log/run-failing.log" \
    --record "$BAD_RECORD"

t=$(now)
smk "$W/cluster" "$W/log/run-cluster.log" "${SLURM_ARGS[@]}" --configfile config/test.yaml \
    || { say "FAILED: rerun on SLURM, see $W/log/run-cluster.log"; tail -n 40 "$W/log/run-cluster.log"; exit 1; }
say "3. fixed rerun on SLURM: $(took "$t") s"

smk "$W/cluster" "$W/log/dryrun-cluster.log" -n --cores 2 --configfile config/test.yaml
t=$(now)
python "$REPO/tests/cluster/check.py" results --local "$W/local" --cluster "$W/cluster" \
    --dry-run-log "$W/log/dryrun-cluster.log"
say "4. checks: $(took "$t") s"
RUN_S=$(took "$t_run")
say "phase run: ${RUN_S} s"
say "PASSED: apt ${APT_S} s, daemons ${DAEMONS_S} s, run ${RUN_S} s"
OK=1
