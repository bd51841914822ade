#!/usr/bin/env bash
# A single-node Slurm on this machine, for tests and laptops: `batch --runner slurm` without a
# cluster. As root, without systemd or cgroups (it runs in containers).
#
#   tools/slurm-local.sh start    munged, slurmctld and slurmd; waits until the node is idle and
#                                 prints `export SLURM_CONF=...` for the clients (sbatch, squeue)
#   tools/slurm-local.sh stop     stops the daemons it started (by their pid files), newest first
#   tools/slurm-local.sh status   says whether they run and what sinfo says
#
# Everything lives in $NAO_SLURM_DIR (default /tmp/nao-slurm): slurm.conf, state, spool, logs,
# pid files. Needs Debian's slurm-wlm and munge (.ci/install-deps.sh). Facts behind the settings:
# docs/scaling.md.
set -euo pipefail

dir=${NAO_SLURM_DIR:-/tmp/nao-slurm}
conf=$dir/slurm.conf
node=$(hostname -s)
say() { echo "slurm-local: $*" >&2; }
die() { say "$*"; exit 1; }

alive() { [ -f "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null; }

write_conf() {
  local cpus mem
  cpus=$(nproc)
  mem=$(($(awk '/MemTotal/ {print int($2 / 1024)}' /proc/meminfo) - 512))
  mkdir -p "$dir/state" "$dir/spool" "$dir/log"
  chown slurm:slurm "$dir/state" "$dir/log"
  cat > "$conf" <<EOF
# Written by tools/slurm-local.sh: one node, no cgroups, no accounting.
ClusterName=nao-local
SlurmctldHost=$node(127.0.0.1)
SlurmUser=slurm
SlurmdUser=root
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MaxArraySize=${NAO_SLURM_MAX_ARRAY:-10001}
SchedulerParameters=batch_sched_delay=0,sched_min_interval=0
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldPort=${NAO_SLURM_PORT:-6817}
SlurmdPort=$((${NAO_SLURM_PORT:-6817} + 1))
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=batch Nodes=$node Default=YES State=UP MaxTime=INFINITE
EOF
}

start() {
  [ "$(id -u)" -eq 0 ] || die "start needs root (munged runs as munge, slurmctld as slurm)"
  for b in munged slurmctld slurmd sinfo; do
    command -v "$b" >/dev/null || [ -x "/usr/sbin/$b" ] || die "$b is not installed (apt-get install slurm-wlm munge)"
  done
  mkdir -p "$dir"
  if ! alive "$dir/munged.pid"; then
    if pgrep -x munged >/dev/null && [ -S /run/munge/munge.socket.2 ]; then
      say "munged already runs (not ours): using it"
    else
      mkdir -p /run/munge /var/lib/munge /var/log/munge
      chown munge:munge /run/munge /var/lib/munge /var/log/munge
      chmod 0755 /run/munge
      [ -f /etc/munge/munge.key ] || die "/etc/munge/munge.key is missing (reinstall munge, or run mungekey as munge)"
      # munged writes its pid file as munge, into a folder of its own.
      mkdir -p "$dir/munge"
      chown munge:munge "$dir/munge"
      if runuser -u munge -- /usr/sbin/munged --force --pid-file="$dir/munge/munged.pid" 2>>"$dir/munged.err"; then
        for _ in $(seq 50); do [ -s "$dir/munge/munged.pid" ] && break; sleep 0.1; done
        [ -s "$dir/munge/munged.pid" ] || die "munged wrote no pid file ($dir/munged.err)"
        cp "$dir/munge/munged.pid" "$dir/munged.pid"
      elif pgrep -x munged >/dev/null && [ -S /run/munge/munge.socket.2 ]; then
        say "munged started beside us (not ours): using it"
      else
        die "munged did not start: $(tail -n1 "$dir/munged.err")"
      fi
    fi
  fi
  if ! alive "$dir/slurmctld.pid"; then
    write_conf
    /usr/sbin/slurmctld -f "$conf" -i || die "slurmctld did not start (see $dir/log/slurmctld.log)"
  fi
  if ! alive "$dir/slurmd.pid"; then
    /usr/sbin/slurmd -f "$conf" -N "$node" || die "slurmd did not start (see $dir/log/slurmd.log)"
  fi
  export SLURM_CONF=$conf
  local deadline=$((SECONDS + 30)) state=""
  while [ $SECONDS -lt $deadline ]; do
    state=$(timeout 5 sinfo -h -N -n "$node" -o %t 2>/dev/null || true)
    if [ "$state" = idle ] || [ "$state" = mix ] || [ "$state" = alloc ]; then
      say "node $node is $state ($dir)"
      echo "export SLURM_CONF=$conf"
      return 0
    fi
    sleep 0.5
  done
  die "the node did not become idle in 30 s (sinfo: '${state:-nothing}'; logs in $dir/log)"
}

stop() {
  local stopped=0
  for d in slurmd slurmctld munged; do
    # Another Slurm on this machine (a second test's) may authenticate through our munged.
    if [ "$d" = munged ] && pgrep -x slurmctld >/dev/null; then
      alive "$dir/munged.pid" && say "munged left running: another Slurm here uses it"
      rm -f "$dir/munged.pid"
      continue
    fi
    if alive "$dir/$d.pid"; then
      local pid
      pid=$(cat "$dir/$d.pid")
      kill "$pid"
      for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
      kill -0 "$pid" 2>/dev/null && kill -9 "$pid"
      stopped=$((stopped + 1))
    fi
    rm -f "$dir/$d.pid"
  done
  say "stopped $stopped daemon(s)"
}

status() {
  local all=0
  for d in munged slurmctld slurmd; do
    if alive "$dir/$d.pid"; then say "$d runs (pid $(cat "$dir/$d.pid"))"; else say "$d does not run"; all=1; fi
  done
  [ -f "$conf" ] && SLURM_CONF=$conf timeout 10 sinfo 2>&1 | sed 's/^/slurm-local: /' >&2 || true
  return $all
}

case "${1:-}" in
  start) start ;;
  stop) stop ;;
  status) status ;;
  *) echo "usage: tools/slurm-local.sh start|stop|status" >&2; exit 2 ;;
esac
