#!/usr/bin/env bash
# Our pipeline against the llvmpipe peer, interleaved: each round runs, per workload, one process
# with our benchmark and the peer's (1 and 2 threads) back to back, so slow phases of a shared
# machine hit both alike. Prints, per workload, the median ms per frame over the rounds and the
# ratios ours / peer. (Google Benchmark 1.7.1's --benchmark_enable_random_interleaving aborts
# when repetitions end with different iteration counts, hence separate processes.)
#
#   bench/compare_with_peer.sh [rounds=3] [rast_bench=build/bench/rast_bench]
set -euo pipefail

rounds=${1:-3}
bench=${2:-build/bench/rast_bench}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# label;our benchmark;the peer's, with @ standing for its thread count
workloads=(
  "W1;BM_FrameW1/;BM_PeerW1/threads:@/"
  "tiny-1;BM_FrameW2Tiny/area:1/;BM_PeerW2Tiny/threads:@/area:1/"
  "tiny-10;BM_FrameW2Tiny/area:10/;BM_PeerW2Tiny/threads:@/area:10/"
  "tiny-100;BM_FrameW2Tiny/area:100/;BM_PeerW2Tiny/threads:@/area:100/"
  "tiny-1000;BM_FrameW2Tiny/area:1000/;BM_PeerW2Tiny/threads:@/area:1000/"
  "W3 front-to-back;BM_FrameW3FrontToBack/;BM_PeerW3FrontToBack/threads:@/"
  "W3 back-to-front;BM_FrameW3BackToFront/;BM_PeerW3BackToFront/threads:@/"
  "W3 tess front-to-back;BM_FrameW3TessFrontToBack/;BM_PeerW3TessFrontToBack/threads:@/"
  "W3 tess back-to-front;BM_FrameW3TessBackToFront/;BM_PeerW3TessBackToFront/threads:@/"
  "W4;BM_FrameW4/;BM_PeerW4/threads:@/"
)

for ((r = 0; r < rounds; ++r)); do
  for ((w = 0; w < ${#workloads[@]}; ++w)); do
    IFS=';' read -r _ ours peer <<<"${workloads[w]}"
    "$bench" --benchmark_filter="^(${ours}|${peer/@/[12]})" \
      --benchmark_out="$out/r$r-w$w.json" --benchmark_out_format=json >/dev/null 2>"$out/log"
    grep -i "skipped" "$out/log" >&2 || true
  done
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

print(f"{'workload':24}{'ours ms':>10}{'peer 1t':>10}{'peer 2t':>10}{'ours/1t':>10}{'ours/2t':>10}")
for w in workloads:
    label, ours, peer = w.split(";")
    o, p1, p2 = median(ours), median(peer.replace("@", "1")), median(peer.replace("@", "2"))
    print(f"{label:24}{o:10.2f}{p1:10.2f}{p2:10.2f}{o / p1:10.2f}{o / p2:10.2f}")
PY
