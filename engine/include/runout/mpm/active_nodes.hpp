#pragma once
// The nodes of the grid box that this step's particles reach, as runs along
// node rows, and the CPU backend's node loops over them. A long or
// diagonal slide's box is mostly empty (the escarpment's deposit and relict
// span a box some 420 m by 60 m that its 12 m thick layer crosses
// diagonally), and the node stages are pointwise, so the empty nodes need
// neither clearing nor updating: nothing reads them.
//
// What p2g adds into (mass, volume, momentum, force; the gap at +infinity)
// and the base's force are kept clear on every node outside the runs:
// clear() empties the last step's runs before the box moves, and a box
// that needs more storage is cleared whole. Sums over the nodes and the
// grid's totals then read the same as a dense grid's.
#include <algorithm>
#include <vector>

#include "runout/mpm/grid.hpp"
#include "runout/mpm/lanes.hpp"

namespace runout {

class ActiveNodes {
 public:
  // Nodes a loop hands out at a time, and the pieces of a sum.
  static constexpr int kChunk = 1024;

  struct Run {
    int begin, end;  // box node indices [begin, end) along one node row
  };

  // The runs from the occupied blocks of block x block cells:
  // occupied(bi, by). A particle in cell c reaches nodes c-1 .. c+2, and
  // the stencil's rows along x one more, c+3 (grid.hpp, place_box).
  template <class Occupied>
  void find(const GridView& g, int block, int blocks_x, int blocks_y, Occupied occupied) {
    occupied_.resize(static_cast<std::size_t>(blocks_x) * blocks_y);
    for (int by = 0; by < blocks_y; ++by)
      for (int bi = 0; bi < blocks_x; ++bi) occupied_[by * blocks_x + bi] = occupied(bi, by);
    runs_.clear();
    row_.resize(blocks_x);
    for (int j = 0; j < g.ny; ++j) {
      // The block rows whose nodes reach row j: block by - 1 <= j <= block by + block + 1.
      const int by0 = std::max(0, (j - 2) / block), by1 = std::min(blocks_y - 1, (j + 1) / block);
      std::fill(row_.begin(), row_.end(), 0);
      for (int by = by0; by <= by1; ++by) {
        const char* const o = occupied_.data() + static_cast<std::size_t>(by) * blocks_x;
        for (int bi = 0; bi < blocks_x; ++bi) row_[bi] |= o[bi];
      }
      for (int bi = 0; bi < blocks_x;) {
        if (!row_[bi]) {
          ++bi;
          continue;
        }
        const int first = bi;
        while (bi < blocks_x && row_[bi]) ++bi;
        // cells block first .. block bi - 1: node columns from one before to three after
        add_run(g, j, block * first - 1, block * bi + 2);
      }
    }
    finish();
  }
  // Every node of the box (a periodic scene, whose seam exchange reads the
  // columns at both ends of every row).
  void whole(const GridView& g) {
    runs_.clear();
    for (int j = 0; j < g.ny; ++j) add_run(g, j, 0, g.nx - 1);
    finish();
  }

  // Empties what p2g adds into and the base's force on the runs, before
  // the box moves.
  void clear(const GridView& g) {
    for_each([&](int n) { clear_node(g, n); });
    runs_.clear();
  }
  // The whole box, where its storage was just made: what std::vector adds
  // is zero, and the gap must be +infinity.
  static void clear_all(const GridView& g) {
    const int n = g.size();
#pragma omp parallel for schedule(static) if (n > 4 * kChunk)
    for (int i = 0; i < n; ++i) clear_node(g, i);
  }

  // f(n) for each node of the runs, in parallel.
  template <class F>
  void for_each(F f) const {
    const int runs = static_cast<int>(runs_.size());
#pragma omp parallel for schedule(dynamic, 1) firstprivate(f) if (nodes_ > 4 * kChunk)
    for (int r = 0; r < runs; ++r)
      for (int n = runs_[r].begin; n < runs_[r].end; ++n) f(n);
  }
  void fill(double* a, double v) const {
    for_each([=](int n) { a[n] = v; });
  }

  // The sum of a over the box, zero off the runs, in fixed pieces of kChunk
  // nodes from node 0, each in four interleaved partial sums, the pieces'
  // sums added in order: the same bits on any number of threads, and as a
  // sum over every node (a piece with no run adds an exact zero). One sum
  // in node order was a chain of dependent additions, on one thread while
  // the others waited.
  double sum(const double* a, int count) {
    const int pieces = (count + kChunk - 1) / kChunk;
    piece_sums_.assign(pieces, 0.0);
    double* const sums = piece_sums_.data();
    const int* const touched = touched_pieces_.data();
    const int n_touched = static_cast<int>(touched_pieces_.size());
#pragma omp parallel for schedule(static) if (nodes_ > 4 * kChunk)
    for (int t = 0; t < n_touched; ++t) {
      const int r = touched[t];
      const int i0 = r * kChunk, i1 = std::min(count, i0 + kChunk);
      Lanes partial = splat(0.0);
      int i = i0;
      for (; i + 4 <= i1; i += 4) partial = partial + load_lanes(a + i);
      double total = (lane(partial, 0) + lane(partial, 1)) + (lane(partial, 2) + lane(partial, 3));
      for (; i < i1; ++i) total += a[i];
      sums[r] = total;
    }
    double total = 0;
    for (int r = 0; r < pieces; ++r) total += sums[r];
    return total;
  }

  int nodes() const { return nodes_; }

 private:
  // Columns [c0, c1] of row j, clamped to the box, in runs of at most
  // kChunk nodes.
  void add_run(const GridView& g, int j, int c0, int c1) {
    c0 = std::max(c0, 0);
    c1 = std::min(c1, g.nx - 1);
    for (int c = c0; c <= c1; c += kChunk)
      runs_.push_back({g.index(c, j), g.index(std::min(c1 + 1, c + kChunk), j)});
  }
  void finish() {
    nodes_ = 0;
    touched_pieces_.clear();
    for (const Run& r : runs_) {
      nodes_ += r.end - r.begin;
      for (int piece = r.begin / kChunk; piece <= (r.end - 1) / kChunk; ++piece)
        if (touched_pieces_.empty() || touched_pieces_.back() < piece)
          touched_pieces_.push_back(piece);
    }
  }

  std::vector<Run> runs_;  // in node order
  std::vector<int> touched_pieces_;  // sum's pieces that hold a run, increasing
  std::vector<char> occupied_, row_;  // find's: by block, and a node row's blocks
  std::vector<double> piece_sums_;
  int nodes_ = 0;
};

}  // namespace runout
