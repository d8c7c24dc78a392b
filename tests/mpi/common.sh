# Shared by the MPI tests: mpirun as CI runs it (root, more ranks than cores, no binding), a
# timeout on every run, small images, and a comparison with single-process strahl.
set -u
MPI_BIN=$1 CLI=$2 SRC=$3
shift 3
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_hwloc_base_binding_policy=none
# No shared-memory transport warnings in containers without /dev/shm space.
export OMPI_MCA_btl_vader_single_copy_mechanism=none
. "$(dirname "${BASH_SOURCE[0]}")/../checks.sh"

# mpirun_strahl NP ARGS...: strahl-mpi on NP ranks, at most 60 s.
mpirun_strahl() {
  local np=$1
  shift
  timeout -k 5 60 mpirun -np "$np" "$MPI_BIN" "$@"
}
