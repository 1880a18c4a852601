#!/usr/bin/env bash
# Starts a single-node Slurm cluster on this machine (munged, slurmctld,
# slurmd), for `fabmesh batch --slurm` and its CI step. Runs as root without
# systemd (containers included); idempotent: what runs already is left alone.
# Debian's slurm-wlm and munge come from scripts/install-deps.sh --test.
#
#   scripts/slurm-single-node.sh          start (or check) the cluster, print the SLURM_CONF line
#   scripts/slurm-single-node.sh stop     stop the daemons this script started
#
# State (config, spool, logs, pid files) lives in $FABMESH_SLURM_DIR
# (default /var/tmp/fabmesh-slurm). Clients need `export SLURM_CONF=$FABMESH_SLURM_DIR/slurm.conf`.
set -euo pipefail

state="${FABMESH_SLURM_DIR:-/var/tmp/fabmesh-slurm}"
conf="$state/slurm.conf"
host="$(hostname -s)"
export SLURM_CONF="$conf"

say() { echo "slurm-single-node: $*" >&2; }
die() { say "$*"; exit 1; }
alive() { [[ -f "$1" ]] && kill -0 "$(cat "$1")" 2>/dev/null; }

stop() {
  for pidfile in "$state/slurmd.pid" "$state/slurmctld.pid" "$state/munged.pid"; do
    if alive "$pidfile"; then
      kill "$(cat "$pidfile")" && say "stopped $(basename "$pidfile" .pid)"
    fi
  done
}

if [[ "${1:-}" == "stop" ]]; then
  stop
  exit 0
fi

[[ $(id -u) -eq 0 ]] || die "must run as root (slurmd starts jobs as their user)"
for tool in munged slurmctld slurmd sinfo scontrol; do
  command -v "$tool" >/dev/null || die "$tool is missing: run scripts/install-deps.sh --test (slurm-wlm, munge)"
done
mkdir -p "$state"/{ctld,spool,log}

# munge: the key exists once installed; the socket folder is created at each boot.
munge_socket=/run/munge/munge.socket.2
install -d -o munge -g munge -m 0755 /run/munge
install -d -o munge -g munge -m 0700 /var/lib/munge /var/log/munge
if [[ ! -f /etc/munge/munge.key ]]; then
  say "creating /etc/munge/munge.key"
  dd if=/dev/urandom of=/etc/munge/munge.key bs=1 count=1024 status=none
  chown munge:munge /etc/munge/munge.key
  chmod 0400 /etc/munge/munge.key
fi
if alive "$state/munged.pid" && [[ -S $munge_socket ]]; then
  say "munged runs (pid $(cat "$state/munged.pid"))"
else
  # munged runs as its own user, which writes its pid file in its own folder.
  runuser -u munge -- munged --pid-file=/run/munge/munged.pid --force
  for _ in $(seq 50); do [[ -S $munge_socket && -s /run/munge/munged.pid ]] && break; sleep 0.1; done
  cp /run/munge/munged.pid "$state/munged.pid"
  say "started munged (pid $(cat "$state/munged.pid"))"
fi
munge -n </dev/null | unmunge >/dev/null || die "munge does not work (see /var/log/munge/munged.log)"

# The configuration: this host, its CPUs and memory; no cgroups, no accounting database.
cpus="$(nproc)"
memory_mb="$(awk '/MemTotal/ {print int($2 / 1024 * 0.9)}' /proc/meminfo)"
cat >"$conf.new" <<EOF
# Written by scripts/slurm-single-node.sh: a one-node cluster on $host.
ClusterName=fabmesh
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$state/spool
SlurmctldPidFile=$state/slurmctld.pid
SlurmdPidFile=$state/slurmd.pid
SlurmctldLogFile=$state/log/slurmctld.log
SlurmdLogFile=$state/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
SlurmdTimeout=300
InactiveLimit=0
MinJobAge=300
KillWait=5
MaxArraySize=10001
NodeName=$host CPUs=$cpus RealMemory=$memory_mb State=UNKNOWN
PartitionName=batch Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
if [[ -f $conf ]] && cmp -s "$conf" "$conf.new"; then
  rm "$conf.new"
else
  mv "$conf.new" "$conf"
  # A changed configuration needs fresh daemons.
  if alive "$state/slurmd.pid" || alive "$state/slurmctld.pid"; then
    say "configuration changed: restarting the daemons"
    for pidfile in "$state/slurmd.pid" "$state/slurmctld.pid"; do
      if alive "$pidfile"; then kill "$(cat "$pidfile")"; fi
    done
    sleep 1
  fi
fi

if alive "$state/slurmctld.pid"; then
  say "slurmctld runs (pid $(cat "$state/slurmctld.pid"))"
else
  slurmctld -f "$conf"
  say "started slurmctld"
fi
if alive "$state/slurmd.pid"; then
  say "slurmd runs (pid $(cat "$state/slurmd.pid"))"
else
  slurmd -f "$conf"
  say "started slurmd"
fi

# Ready when the node accepts work.
for _ in $(seq 60); do
  node_state="$(sinfo -h -n "$host" -o %t 2>/dev/null || true)"
  case "$node_state" in
    idle* | mix* | alloc*) break ;;
    drain* | down*) scontrol update nodename="$host" state=resume >/dev/null 2>&1 || true ;;
  esac
  sleep 1
done
case "${node_state:-}" in
  idle* | mix* | alloc*) ;;
  *) die "node $host is '${node_state:-unknown}' after 60 s (logs: $state/log)" ;;
esac
say "node $host is $node_state with $cpus CPUs"
echo "export SLURM_CONF=$conf"
