#!/usr/bin/env bash
# A real single-node SLURM cluster on loopback, for testing the SLURM profile.
# Debian, as root, no systemd.  Usage:  scripts/slurm_local.sh start|stop|status
#   start: installs munge/slurmctld/slurmd/slurm-client if missing, writes a slurm.conf for
#          one node named after `hostname -s` at 127.0.0.1 with this machine's CPUs and
#          memory, starts the daemons in the background, waits until the node is idle,
#          and prints `export SLURM_CONF=...` for the clients (sbatch, squeue, snakemake).
#   stop:  ends exactly the daemons that `start` started (pids recorded in the state dir,
#          each checked to still be that daemon) and removes the slurm.conf it wrote; a state
#          dir that `start` did not use (MECHREPRO_SLURM_DIR set otherwise) is refused, and
#          nothing is touched.
# The config goes to Debian's default /etc/slurm/slurm.conf, because srun inside a job does
# not inherit SLURM_CONF; an existing slurm.conf not written by this script is never touched.
set -euo pipefail
STATE=${MECHREPRO_SLURM_DIR:-/tmp/mechrepro-slurm}
CONF=${MECHREPRO_SLURM_CONF:-/etc/slurm/slurm.conf}   # another path only for tests
MARK="# one node on loopback, written by scripts/slurm_local.sh"
PARTITION=${MECHREPRO_SLURM_PARTITION:-debug}

log() { echo "[slurm_local] $*" >&2; }

install_packages() {
  if command -v slurmctld >/dev/null && command -v slurmd >/dev/null && command -v sbatch >/dev/null \
     && command -v munged >/dev/null; then
    return
  fi
  log "installing munge slurmctld slurmd slurm-client (Debian packages)"
  # keep package scripts from starting services (no systemd here; we start what we need)
  printf '#!/bin/sh\nexit 101\n' > /usr/sbin/policy-rc.d && chmod +x /usr/sbin/policy-rc.d
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq munge slurmctld slurmd slurm-client >/dev/null
  rm -f /usr/sbin/policy-rc.d
}

start_munge() {
  if munge -n 2>/dev/null | unmunge >/dev/null 2>&1; then
    log "munge already running (not ours, left alone)"
    return
  fi
  [ -s /etc/munge/munge.key ] || { mungekey --create --force 2>/dev/null || dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 2>/dev/null; }
  chown munge:munge /etc/munge/munge.key && chmod 400 /etc/munge/munge.key
  mkdir -p /run/munge /var/log/munge /var/lib/munge
  chown munge:munge /run/munge /var/log/munge /var/lib/munge
  runuser -u munge -- /usr/sbin/munged
  for _ in $(seq 50); do [ -s /run/munge/munged.pid ] && break; sleep 0.1; done
  cp /run/munge/munged.pid "$STATE/munged.pid"
}

write_conf() {
  local host cpus mem
  host=$(hostname -s)
  cpus=$(nproc)
  mem=$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 * 9 / 10 ))
  if [ -s "$CONF" ] && ! grep -qF "$MARK" "$CONF"; then
    log "$CONF exists and is not ours: refusing to overwrite it"
    exit 1
  fi
  mkdir -p "$(dirname "$CONF")"
  cat > "$CONF" <<CONF
$MARK
ClusterName=mechrepro
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/affinity
ReturnToService=2
# finished jobs stay visible to squeue/scontrol long enough for the plugin's status checks
MinJobAge=900
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
StateSaveLocation=$STATE/state
SlurmdSpoolDir=$STATE/spool
SlurmctldPidFile=$STATE/slurmctld.pid
SlurmdPidFile=$STATE/slurmd.pid
SlurmctldLogFile=$STATE/slurmctld.log
SlurmdLogFile=$STATE/slurmd.log
SlurmctldPort=6817
SlurmdPort=6818
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=$PARTITION Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
}

start() {
  local t0=$SECONDS
  if [ -s "$STATE/slurmctld.pid" ] && kill -0 "$(cat "$STATE/slurmctld.pid")" 2>/dev/null; then
    log "already running (pids in $STATE)"
    echo "export SLURM_CONF=$CONF"
    return
  fi
  install_packages
  mkdir -p "$STATE/state" "$STATE/spool"
  start_munge
  write_conf
  export SLURM_CONF=$CONF
  slurmctld -f "$CONF"
  slurmd -f "$CONF"
  for _ in $(seq 120); do
    state=$(sinfo -h -o %t 2>/dev/null | head -1 || true)
    [ "$state" = "idle" ] && break
    sleep 1
  done
  if [ "${state:-}" != "idle" ]; then
    log "node did not become idle (state '${state:-none}'); logs in $STATE"
    tail -5 "$STATE"/slurmctld.log "$STATE"/slurmd.log >&2 || true
    stop
    exit 1
  fi
  log "cluster up in $((SECONDS - t0)) s: partition $PARTITION, node $(hostname -s) idle"
  echo "export SLURM_CONF=$CONF"
}

# The state directory of the cluster our slurm.conf was written for (empty: none of ours).
conf_state() {
  if [ -f "$CONF" ] && grep -qF "$MARK" "$CONF"; then
    sed -n 's|^StateSaveLocation=\(.*\)/state$|\1|p' "$CONF" | head -1
  fi
}

stop() {
  local ours pid f d
  ours=$(conf_state)
  # another state dir than start's: it holds no pids of these daemons, and removing the conf
  # would leave them running without one
  if [ -n "$ours" ] && [ "$(realpath -m "$ours")" != "$(realpath -m "$STATE")" ]; then
    log "refusing to stop: $CONF belongs to the cluster started with state dir $ours, not $STATE" \
        "(MECHREPRO_SLURM_DIR=$ours $0 stop); nothing touched"
    exit 1
  fi
  if [ -z "$ours" ] && ! compgen -G "$STATE/*.pid" >/dev/null; then
    log "refusing to stop: nothing was started with state dir $STATE; nothing touched"
    exit 1
  fi
  for d in slurmd slurmctld munged; do
    f=$STATE/$d.pid
    [ -s "$f" ] || continue
    pid=$(cat "$f")
    if [ "$(cat "/proc/$pid/comm" 2>/dev/null)" != "$d" ]; then
      log "pid $pid of $f is not $d (it ended; the pid may be reused): left alone"
    elif kill "$pid" 2>/dev/null; then
      for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
      log "stopped $d ($pid)"
    fi
    rm -f "$f"
  done
  # With a slurm.conf but no controller, `scontrol show config` blocks for 10 s, and the
  # SLURM executor plugin runs it on import, i.e. at every snakemake start: remove ours.
  if [ -n "$ours" ]; then
    rm -f "$CONF"
  fi
}

status() { SLURM_CONF=$CONF sinfo; SLURM_CONF=$CONF squeue; }

case "${1:-}" in
  start) start ;;
  stop) stop ;;
  status) status ;;
  *) echo "usage: $0 start|stop|status" >&2; exit 2 ;;
esac
