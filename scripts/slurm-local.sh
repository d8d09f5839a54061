#!/usr/bin/env bash
# A one-machine Slurm for trying scripts/slurm-frames.sh here: munge for authentication, slurmctld and
# slurmd on localhost, without systemd (Debian 12's slurm-wlm and munge: scripts/install-deps.sh
# --with-slurm). Needs root.
#   scripts/slurm-local.sh start    configure (only files it wrote itself are replaced) and start
#   scripts/slurm-local.sh stop     stop the daemons this script started (by their pid files)
#   scripts/slurm-local.sh status   exit 0 when the node answers, idle or busy
# Exit codes: 0 ok, 1 failure, 3 Slurm or munge not installed, 4 not root.
set -euo pipefail
state=/run/groom-slurm          # pid files of what this script started
conf=/etc/slurm/slurm.conf
marker="# written by groom scripts/slurm-local.sh"

have() { command -v "$1" >/dev/null 2>&1; }
node_up() { sinfo -h -o '%T' 2>/dev/null | grep -qE '^(idle|mixed|allocated|completing)'; }

start() {
  for b in munged slurmctld slurmd sinfo sbatch; do
    have "$b" || { echo "slurm-local: $b not found (scripts/install-deps.sh --with-slurm)" >&2; exit 3; }
  done
  [[ $(id -u) -eq 0 ]] || { echo "slurm-local: needs root to start munged, slurmctld and slurmd" >&2; exit 4; }
  mkdir -p "$state" /etc/munge /run/munge /var/lib/munge /var/log/munge
  if [[ ! -s /etc/munge/munge.key ]]; then
    dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 status=none
  fi
  chown -R munge:munge /etc/munge /run/munge /var/lib/munge /var/log/munge
  chmod 400 /etc/munge/munge.key
  if ! munge -n </dev/null >/dev/null 2>&1; then
    runuser -u munge -- munged --force
    pgrep -u munge -n munged > "$state/munged.pid"
  fi
  if [[ ! -f "$conf" ]] || grep -qF "$marker" "$conf"; then
    local host cpus mem
    host=$(hostname -s)
    cpus=$(nproc)
    mem=$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 * 9 / 10 ))
    mkdir -p /etc/slurm /var/spool/slurmctld /var/spool/slurmd /var/log/slurm
    cat > "$conf" <<CONF
$marker
ClusterName=groom
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldPidFile=$state/slurmctld.pid
SlurmdPidFile=$state/slurmd.pid
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
ReturnToService=2
MaxArraySize=100001
NodeName=$host CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=frames Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
  else
    echo "slurm-local: $conf exists and was not written by this script; using it as it is" >&2
  fi
  pgrep -x slurmctld >/dev/null || slurmctld
  pgrep -x slurmd >/dev/null || slurmd
  for _ in $(seq 1 30); do
    if node_up; then echo "slurm-local: node $(hostname -s) up"; return 0; fi
    sleep 1
  done
  echo "slurm-local: the node did not come up in 30 s (see /var/log/slurm/*.log)" >&2
  sinfo >&2 || true
  exit 1
}

stop() {
  local pid
  for d in slurmd slurmctld munged; do
    if [[ -s "$state/$d.pid" ]]; then
      pid=$(cat "$state/$d.pid")
      kill "$pid" 2>/dev/null || true
      # Wait (up to 10 s) so that a start right after finds it gone.
      for _ in $(seq 1 20); do kill -0 "$pid" 2>/dev/null || break; sleep 0.5; done
      rm -f "$state/$d.pid"
    fi
  done
}

case "${1:-}" in
  start) start ;;
  stop) stop ;;
  status) node_up ;;
  *) echo "usage: $0 start|stop|status" >&2; exit 2 ;;
esac
