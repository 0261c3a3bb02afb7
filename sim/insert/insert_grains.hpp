#pragma once
// One insertion: places up to `count` new grains in a region of a scene so
// that none overlaps another grain, a wall or a grain placed before it
// (checked exactly, obstacles.hpp). Two methods:
//
//  * random: uniform random trial positions (and orientations) in the
//    region, each checked exactly, until the count is reached, `attempts`
//    consecutive trials failed, or the time budget is spent.
//
//  * fft: the configuration-space obstacle of the seed (Sec. 3.2, 4.1). For
//    each trial orientation R the overlap volume V(t) of the grain's cover
//    balls, inflated by a margin delta, with the scene's balls is computed
//    at every node t of a grid over the region by one correlation in Fourier
//    space (contact/correlation SceneOverlap: the scene's spectrum once, one
//    shape spectrum and one inverse FFT per orientation). Where the true
//    grain would touch a scene ball the inflated one penetrates it by at
//    least delta, so V >= lens(r + s, r, s + delta) there (r the smallest
//    scene ball, s the grain's largest ball; a position where only a
//    smaller ball of a clump touches may pass and is then rejected by the
//    exact check); nodes with V <= half of that are the candidates.
//    Ellipsoids that turn use one field per round, of their core (the ball
//    of the smallest semi-axis about the centre, inside the grain in every
//    orientation: where the grain fits in some orientation its core fits),
//    and draw each trial's orientation at random.
//    They are visited in a random order (seeded), each confirmed by the exact
//    check against the scene, the walls and the grains placed so far; then
//    random points in the cells of near-free nodes (V below 4 lens volumes
//    at the penetration delta + h sqrt(3)/2: pockets between nodes), a few
//    each. Then a pocket search: random points in the cells of the round's
//    free and near-free nodes, cells drawn uniformly (grains that turn: every
//    other trial in a fresh random orientation). Free space only shrinks as
//    grains are placed, so those cells keep holding the places left, at a
//    far higher hit rate than trials over the whole region; it stops after
//    4 failures per cell in a row, but not before it has run as long as the
//    round's fields took. Then the field is recomputed with the new grains
//    in the scene, new trial orientations and the nodes shifted by a random
//    fraction of a cell, until two rounds in a row place nothing or the
//    budget is spent. Each orientation's candidates are visited as soon as
//    its field is ready.
//
// The scene enters as balls: spheres and clump balls as they are, ellipsoids
// by their conservative ball covers (grain_geometry.hpp), radii rounded up to
// classes 5 % apart (one NUFFT spreading pass per class). Only balls that can
// reach the region take part. Along periodic axes the images are included.
// The field is computed for the largest grain of a size distribution; the
// exact check decides for the grain actually placed.
#include <cstdint>
#include <random>
#include <vector>

#include "sim/scene/scene_config.hpp"

namespace grains::sim::insert {

/// What an insertion sees of the scene: every grain of every rank.
struct SceneGrains {
  std::vector<Vec3> sphere_x;  // spheres and clump balls
  std::vector<double> sphere_r;
  std::vector<Vec3> ell_x, ell_axes;  // ellipsoids
  std::vector<Quat> ell_q;
};

struct NewGrain {
  Vec3 x;    // centre (centre of mass of a clump)
  double r;  // bounding radius
  Quat o;    // orientation, body -> world
};

struct InsertStats {
  std::int64_t requested = 0, placed = 0;
  std::int64_t trials = 0;      // exact checks of candidate grains
  std::int64_t candidates = 0;  // fft: candidate (node, orientation) pairs found
  int fields = 0;               // fft: overlap fields computed
  int rounds = 0;               // fft: field recomputations + 1
  double field_seconds = 0;     // fft: time in the overlap fields
  double seconds = 0;           // total wall-clock time
};

/// Places up to c.grains.count grains; seed makes it reproducible (one seed
/// per insertion). `threads`: for the FFTs (0: OpenMP's count).
std::vector<NewGrain> insert_grains(const InsertionConfig& c, const SceneGrains& scene, const Domain& domain,
                                    const Walls& walls, std::uint64_t seed, int threads, InsertStats* stats = nullptr);

/// A uniformly distributed rotation (Shoemake's method).
Quat uniform_rotation(std::mt19937_64& rng);

}  // namespace grains::sim::insert
