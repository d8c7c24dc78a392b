#!/usr/bin/env bash
# Over a real network stack: two "hosts" in network namespaces of their own, joined by a veth
# pair; mpirun starts in one and reaches the other through a launcher that enters its namespace
# (plm_rsh_agent, in place of ssh); ranks talk TCP over the veth only (--mca btl tcp,self). The
# image has the same bytes as strahl's, and the veth carried at least the image's worth of bytes.
# Skipped (exit 77) where network namespaces cannot be made.
. "$(dirname "$0")/common.sh"

id=$$
a=strahl-a-$id b=strahl-b-$id
cleanup() {
  ip netns del "$a" 2> /dev/null
  ip netns del "$b" 2> /dev/null
  rm -rf "$WORK"
}
trap cleanup EXIT
if ! ip netns add "$a" 2> /dev/null || ! ip netns add "$b" 2> /dev/null; then
  echo "skipped: cannot create network namespaces here"
  exit 77
fi
ip link add "va$id" type veth peer name "vb$id" &&
  ip link set "va$id" netns "$a" && ip link set "vb$id" netns "$b" &&
  ip -n "$a" addr add 10.77.0.1/24 dev "va$id" && ip -n "$b" addr add 10.77.0.2/24 dev "vb$id" &&
  ip -n "$a" link set "va$id" up && ip -n "$b" link set "vb$id" up &&
  ip -n "$a" link set lo up && ip -n "$b" link set lo up || { echo "skipped: cannot set up a veth pair"; exit 77; }

cat > "$WORK/agent.sh" << AGENT
#!/bin/sh
# "ssh" to host \$1: run the rest in that host's namespace.
host=\$1; shift
case \$host in 10.77.0.2) ns=$b ;; *) ns=$a ;; esac
exec ip netns exec \$ns sh -c "\$*"
AGENT
chmod +x "$WORK/agent.sh"
printf '10.77.0.1 slots=2\n10.77.0.2 slots=2\n' > "$WORK/hosts"

rx() { ip -n "$a" -s link show "va$id" | awk '/RX:/ { getline; print $1 }'; }
args=("$SRC/scenes/lecture-whitted.yaml" --width 64 --height 36 --sampler sobol --spp 4 --tile-size 8)
"$CLI" "${args[@]}" -q --threads 1 -o "$WORK/ref.pfm" || fail "strahl failed"
before=$(rx)
timeout -k 5 90 ip netns exec "$a" mpirun --hostfile "$WORK/hosts" --map-by node -np 2 \
  --mca plm_rsh_agent "$WORK/agent.sh" --mca btl tcp,self \
  --mca btl_tcp_if_include 10.77.0.0/24 --mca oob_tcp_if_include 10.77.0.0/24 \
  -x OMPI_ALLOW_RUN_AS_ROOT -x OMPI_ALLOW_RUN_AS_ROOT_CONFIRM \
  "$MPI_BIN" "${args[@]}" --threads 1 -o "$WORK/net.pfm" > "$WORK/net.txt" 2>&1 ||
  { cat "$WORK/net.txt"; fail "strahl-mpi across namespaces failed"; }
after=$(rx)
cmp -s "$WORK/ref.pfm" "$WORK/net.pfm" || fail "across namespaces: the image differs"
grep -q "rank 1 .* [1-9][0-9]* tiles" "$WORK/net.txt" || { cat "$WORK/net.txt"; fail "rank 1 rendered no tiles"; }
received=$((after - before))
# Rank 1's results reach rank 0 through the veth: at least the pixel sums of its tiles (8×8
# pixels × 4 doubles each).
tiles=$(sed -n 's/^  rank 1 .* \([0-9][0-9]*\) tiles.*/\1/p' "$WORK/net.txt")
[ "$received" -ge $((${tiles:-1} * 8 * 8 * 32)) ] || fail "only $received bytes crossed the veth for ${tiles:-?} tiles"
[ "$failures" = 0 ] && echo "ok: two namespaces over TCP, rank 1 rendered $tiles tiles, $received bytes received through the veth"
finish
