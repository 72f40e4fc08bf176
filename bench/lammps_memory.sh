#!/usr/bin/env bash
# LAMMPS's own estimate of its memory for the relax case of ../shared/peers/dem (the same data
# file and pair style as lammps-relax.sh, 2,000 steps and then a run of none, whose set-up reports the memory
# with the contacts formed), per particle: the peer figure beside packlab's "engine memory per particle".
# usage: lammps_memory.sh PEERS_DIR   prints "lammps relax memory N=... mbytes=... bytes_per_particle=..."
set -euo pipefail
PEERS=$1
. "$PEERS/common.sh"
command -v lmp >/dev/null 2>&1 || { echo "lammps relax memory: lmp not installed"; exit 0; }
export OMP_NUM_THREADS=1
TMP=$(mktemp -d); trap 'rm -rf "$TMP"' EXIT
cd "$TMP"
write_data data.relax
cat > in.relax <<IN
units           si
atom_style      sphere
atom_modify     map array
boundary        p p p
newton          off
comm_modify     vel yes
read_data       data.relax
neighbor        $(awk -v d=$D 'BEGIN{print 0.1*d}') bin
neigh_modify    delay 0 every 1 check yes
pair_style      gran/hooke/history $KN $KS $GAMMA_N 0.0 $MU 0
pair_coeff      * *
fix             integrate all nve/sphere
timestep        $DT
run             2000
run             0
IN
lmp -in in.relax -log none -nocite > out.txt 2>&1 || { cat out.txt; exit 1; }
awk -v N="$N" '/Per MPI rank memory allocation/ { m = $(NF-1) }
  END { if (m == "") { print "lammps relax memory: not reported"; exit }
        printf "lammps relax memory N=%d mbytes=%s bytes_per_particle=%.0f\n", N, m, m * 1048576 / N }' out.txt
