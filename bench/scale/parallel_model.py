#!/usr/bin/env python3
"""A cost model of a multi-rank grains run, from measured per-rank figures
(docs/parallel.md, "A cost model for many ranks"). It is a model: it predicts,
it does not measure.

  parallel_model.py SERIAL/summary.json RANKS/summary.json [--grains N] [--ranks P]
                    [--latency S] [--bandwidth B]

SERIAL is a serial run of a bed, RANKS the same bed on 2 or more ranks (both
from bench/scale/run.sh, or any run whose summary.json has "ranks"). From them:

  t_pair   seconds per list pair of the pair stage, serial and under the
           ranks' load (the ranks share the machine's memory bandwidth)
  t_grain  seconds per grain-step of every other stage, serial
  k        list pairs per grain (serial)
  rho      grains per unit volume, from the ghost count: the measured ghosts
           of a rank over its ghost-layer volume
  t_ghost  seconds per ghost per step of the neighbour stage beyond the
           serial one (refresh, pack, unpack, waiting), from the ranks run
  k_ghost  list pairs per ghost (the ranks' list pairs beyond k per owned grain)
  bytes    bytes per ghost per refresh

and predicts, for N grains on P ranks in cubic sub-domains of n = N/P grains
(interior ranks, 26 neighbours reached by the three-stage exchange: 6
messages per step), with a network of the given latency and bandwidth:

  step = n (t_grain + k t_pair) + G (t_ghost + k_ghost t_pair)
         + 6 latency + G bytes / bandwidth + ceil(log2 P) latency (the rebuild vote)
  G    = rho ((s + 2 w)^3 - s^3), s = (n / rho)^(1/3), w the ghost cut-off

Rebuild costs (migration, list build) are left out: they are in the measured
neighbour stage per step of the serial run.
"""
import argparse
import json
import math


def load(path):
    s = json.load(open(path))
    s["_n"] = s["particles_end"]
    return s


def stage(s, pred):
    return sum(v for k, v in s["stage_seconds"].items() if pred(k))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("serial")
    ap.add_argument("ranks")
    ap.add_argument("--grains", type=float, default=1e8)
    ap.add_argument("--ranks-count", "--P", dest="P", type=int, default=1000)
    ap.add_argument("--latency", type=float, default=2e-6, help="s per message (default 2 us, InfiniBand class)")
    ap.add_argument("--bandwidth", type=float, default=1e10, help="bytes/s per rank (default 10 GB/s)")
    ap.add_argument("--cutoff", type=float, default=None, help="ghost cut-off (m); default 1.1 d of the bed")
    a = ap.parse_args()

    s1, sp = load(a.serial), load(a.ranks)
    n1, steps1 = s1["_n"], s1["steps"]
    pairs1 = s1["neighbor_pairs_per_step"]
    is_pair = lambda k: "pair_contacts" in k
    t_pair = stage(s1, is_pair) / (pairs1 * steps1)
    t_grain = stage(s1, lambda k: not is_pair(k) and not k.startswith("output")) / (n1 * steps1)
    t_neigh1 = stage(s1, lambda k: k.startswith("neighbor")) / (n1 * steps1)
    k = pairs1 / n1

    r = sp["ranks"]
    P0, steps = sp["mpi_ranks"], sp["steps"]
    owned, ghosts, pairs = r["owned"], r["ghosts"], r["list_pairs"]
    t_pair_loaded = sum(r["pair_seconds"]) / (sum(pairs) * steps)
    extra_neigh = sum(r["neighbor_seconds"]) / steps - t_neigh1 * sum(owned)
    t_ghost = max(0.0, extra_neigh / sum(ghosts))
    k_ghost = max(0.0, (sum(pairs) - k * sum(owned)) / sum(ghosts))
    bytes_per_ghost = sum(r["ghost_bytes_per_step"]) / sum(ghosts)

    # Grain density from the serial bed's volume fraction: 1 mm grains at the
    # bed's packing; w the ghost cut-off (2 r + skin = 1.1 d for bench/scale).
    d = 1e-3
    phi = 0.6
    rho = phi / (math.pi / 6 * d ** 3)
    w = a.cutoff or 1.1 * d
    n = a.grains / a.P
    side = (n / rho) ** (1 / 3)
    G = rho * ((side + 2 * w) ** 3 - side ** 3)

    def step_time(tp):
        compute = n * (t_grain + k * tp)
        ghost = G * (t_ghost + k_ghost * tp)
        comm = 6 * a.latency + G * bytes_per_ghost / a.bandwidth + math.ceil(math.log2(a.P)) * a.latency
        return compute, ghost, comm

    print("measured (serial %d grains; %d ranks):" % (n1, P0))
    print("  t_pair %.1f ns serial, %.1f ns per pair with %d ranks sharing the machine" % (
        t_pair * 1e9, t_pair_loaded * 1e9, P0))
    print("  t_grain %.1f ns, k %.2f pairs per grain, t_ghost %.0f ns, k_ghost %.2f, %.0f bytes per ghost" % (
        t_grain * 1e9, k, t_ghost * 1e9, k_ghost, bytes_per_ghost))
    print("model: %.3g grains on %d ranks: %.3g grains per rank, sub-domain %.1f d wide, %.0f ghosts "
          "(%.1f %%), %.2f MB per step per rank in 6 messages" % (
              a.grains, a.P, n, side / d, G, 100 * G / n, G * bytes_per_ghost / 1e6))
    for label, tp in (("serial t_pair", t_pair), ("loaded t_pair", t_pair_loaded)):
        c, g, m = step_time(tp)
        total = c + g + m
        print("  with the %s: %.1f ms per step (compute %.1f, ghosts %.2f, messages %.3f): "
              "%.3g particle-steps/s, parallel efficiency %.0f %%" % (
                  label, total * 1e3, c * 1e3, g * 1e3, m * 1e3, a.grains / total, 100 * c / total))


if __name__ == "__main__":
    main()
