#!/usr/bin/env bash
# Our pipeline against the llvmpipe peer, interleaved: each round runs, per workload, one process
# with our benchmark and the peer's (1 and 2 threads) back to back, so slow phases of a shared
# machine hit both alike. Prints, per workload, the median ms per frame over the rounds and the
# ratios ours / peer, then W3 against the floor of one write of its colour and depth (a memset,
# measured in the same rounds). (Google Benchmark 1.7.1's --benchmark_enable_random_interleaving
# aborts when repetitions end with different iteration counts, hence separate processes.)
#
#   bench/compare_with_peer.sh [rounds=3] [rast_bench=build/bench/rast_bench]
set -euo pipefail

rounds=${1:-3}
bench=${2:-build/bench/rast_bench}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# label;our benchmark;the peer's, with @ standing for the thread count of both
workloads=(
  "W1;BM_FrameW1/0/threads:@/;BM_PeerW1/threads:@/"
  "tiny-1;BM_FrameW2Tiny/area:1/threads:@/;BM_PeerW2Tiny/threads:@/area:1/"
  "tiny-10;BM_FrameW2Tiny/area:10/threads:@/;BM_PeerW2Tiny/threads:@/area:10/"
  "tiny-100;BM_FrameW2Tiny/area:100/threads:@/;BM_PeerW2Tiny/threads:@/area:100/"
  "tiny-1000;BM_FrameW2Tiny/area:1000/threads:@/;BM_PeerW2Tiny/threads:@/area:1000/"
  "W3 front-to-back;BM_FrameW3FrontToBack/0/threads:@/;BM_PeerW3FrontToBack/threads:@/"
  "W3 back-to-front;BM_FrameW3BackToFront/0/threads:@/;BM_PeerW3BackToFront/threads:@/"
  "W3 tess front-to-back;BM_FrameW3TessFrontToBack/0/threads:@/;BM_PeerW3TessFrontToBack/threads:@/"
  "W3 tess back-to-front;BM_FrameW3TessBackToFront/0/threads:@/;BM_PeerW3TessBackToFront/threads:@/"
  "W4;BM_FrameW4/0/threads:@/;BM_PeerW4/threads:@/"
)

for ((r = 0; r < rounds; ++r)); do
  for ((w = 0; w < ${#workloads[@]}; ++w)); do
    IFS=';' read -r _ ours peer <<<"${workloads[w]}"
    "$bench" --benchmark_filter="^(${ours/@/[12]}|${peer/@/[12]})" \
      --benchmark_out="$out/r$r-w$w.json" --benchmark_out_format=json >/dev/null 2>"$out/log"
    grep -i "skipped" "$out/log" >&2 || true
  done
  # W3's floor in the same rounds: one write of the framebuffer's colour and depth bytes.
  "$bench" --benchmark_filter='^BM_FrameMemsetFloor' --benchmark_out="$out/r$r-floor.json" \
    --benchmark_out_format=json >/dev/null 2>"$out/log"
done

python3 - "$out" "${workloads[@]}" <<'PY'
import glob, json, statistics, sys

out, workloads = sys.argv[1], sys.argv[2:]
times = {}
for path in glob.glob(out + "/*.json"):
    for b in json.load(open(path))["benchmarks"]:
        times.setdefault(b["run_name"], []).append(b["real_time"])

def median(prefix):
    runs = [t for name, ts in times.items() if name.startswith(prefix) for t in ts]
    return statistics.median(runs) if runs else float("nan")

# Ratios are our time / the peer's at the same thread count: below 1 we are faster.
print(f"{'workload':24}{'ours 1t':>9}{'peer 1t':>9}{'ratio':>7}{'ours 2t':>9}{'peer 2t':>9}{'ratio':>7}")
for w in workloads:
    label, ours, peer = w.split(";")
    row = f"{label:24}"
    for t in ("1", "2"):
        o, p = median(ours.replace("@", t)), median(peer.replace("@", t))
        row += f"{o:9.2f}{p:9.2f}{o / p:7.2f}"
    print(row)

# W3 against its floor, one write of colour and depth (a memset, one thread): how many such
# writes each frame costs, ours and the peer's, at 2 threads.
floor = median("BM_FrameMemsetFloor")
print(f"\nfloor: one write of colour and depth (memset, 1 thread) {floor:.3f} ms")
for w in workloads:
    label, ours, peer = w.split(";")
    if label.startswith("W3") and "tess" not in label:
        o, p = median(ours.replace("@", "2")), median(peer.replace("@", "2"))
        print(f"{label} at 2 threads: ours {o / floor:.1f}x the floor, the peer's {p / floor:.1f}x")
PY
