// Traction integrated over a point contact's ellipse (contact/laws/point_contact.hpp): the grid of
// cells on the unit disk, tanh(x)/x, and the cell loop.
//
// The cell loop runs in chunks of cells: first every cell's sliding, tanh(x)/x by its rational
// approximant and forces in one loop over structure-of-arrays tables without branches, which the
// compiler vectorises at the build's baseline instruction set (two cells per SSE2 instruction on
// x86-64; the square root and division are correctly rounded there as in scalar code, so each cell
// has the bits the scalar formula gives); then, in scalar code, the few cells whose tanh argument
// lies beyond the approximant's range or that blend in the friction curve; then the sums, cell by
// cell in grid order as before. The file is compiled with -fno-math-errno (contact/CMakeLists.txt)
// so that std::sqrt needs no errno branch and vectorises; no argument here is negative.
#include "contact/laws/point_contact.hpp"

#include "contact/laws/viscosity.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>

namespace raceway::contact {
namespace {

/// Same bits: true when a and b are the same double, bit for bit.
inline bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

// ---- traction grid -------------------------------------------------------------------------------

// Area and first moments of the part of the unit disk inside [x0, x1] x [y0, y1], exactly:
// the vertical chord at x is [max(y0, -s), min(y1, s)], s = sqrt(1 - x^2); between the abscissae
// where s crosses |y0| and |y1| the chord ends are either constant or +-s, and the integrals of
// 1, x, s, x s, s^2 have closed forms.
struct Moments {
  double area = 0, mx = 0, my = 0;
};

Moments disk_rectangle_moments(double x0, double x1, double y0, double y1) {
  x0 = std::max(x0, -1.0);
  x1 = std::min(x1, 1.0);
  Moments out;
  if (!(x1 > x0)) return out;
  std::array<double, 6> cuts{};
  int n = 0;
  cuts[static_cast<std::size_t>(n++)] = x0;
  cuts[static_cast<std::size_t>(n++)] = x1;
  for (const double y : {y0, y1}) {
    if (std::abs(y) >= 1) continue;
    const double c = std::sqrt(1 - y * y);
    for (const double x : {-c, c})
      if (x > x0 && x < x1) cuts[static_cast<std::size_t>(n++)] = x;
  }
  for (int i = 1; i < n; ++i)  // insertion sort of at most six abscissae
    for (int j = i; j > 0 && cuts[static_cast<std::size_t>(j)] < cuts[static_cast<std::size_t>(j - 1)]; --j)
      std::swap(cuts[static_cast<std::size_t>(j)], cuts[static_cast<std::size_t>(j - 1)]);
  auto root = [](double x) { return std::sqrt(std::max(0.0, 1 - x * x)); };
  auto int_s = [&](double x) { return 0.5 * (x * root(x) + std::asin(std::clamp(x, -1.0, 1.0))); };
  auto int_xs = [&](double x) {
    const double r = root(x);
    return -r * r * r / 3;
  };
  auto int_s2 = [](double x) { return x - x * x * x / 3; };
  for (int i = 0; i + 1 < n; ++i) {
    const double u = cuts[static_cast<std::size_t>(i)], v = cuts[static_cast<std::size_t>(i + 1)];
    if (!(v > u)) continue;
    const double s_mid = root(0.5 * (u + v));
    const bool upper_curve = y1 >= s_mid, lower_curve = y0 <= -s_mid;
    const double hi_mid = upper_curve ? s_mid : y1, lo_mid = lower_curve ? -s_mid : y0;
    if (!(hi_mid > lo_mid)) continue;
    const double d1 = v - u, dx = 0.5 * (v * v - u * u);
    const double ds = int_s(v) - int_s(u), dxs = int_xs(v) - int_xs(u), ds2 = int_s2(v) - int_s2(u);
    // Integrals of the upper end h(x) and lower end l(x): of h, x h, h^2 (same for l).
    const double h = upper_curve ? ds : y1 * d1, xh = upper_curve ? dxs : y1 * dx;
    const double h2 = upper_curve ? ds2 : y1 * y1 * d1;
    const double l = lower_curve ? -ds : y0 * d1, xl = lower_curve ? -dxs : y0 * dx;
    const double l2 = lower_curve ? ds2 : y0 * y0 * d1;
    out.area += h - l;
    out.mx += xh - xl;
    out.my += 0.5 * (h2 - l2);
  }
  return out;
}

// The grid in the unit disk (coordinates x/ax, y/ay), as tables of its cells in grid order (rows
// along x): the cells that overlap the disk, with their exact overlap area, the centroid of the
// overlap and the Hertz pressure shape sqrt(1 - r^2) there.
// The grid is exactly symmetric about both axes: a cell takes the moments of its mirror image in
// x >= 0, y >= 0, the centroid's signs flipped (on an axis: exactly on it), so mirrored cells share
// their shape's bits and the viscosity is evaluated once per distinct shape (5 x 5: 6 for 25 cells).
inline constexpr std::size_t max_distinct_shapes = 64;
struct TractionGrid {
  int gx = 0, gy = 0;
  double shape_integral = 0;   // sum area * shape (-> 2 pi / 3 as the grid refines)
  std::vector<double> x, y;    // centroids, unit disk
  std::vector<double> area;    // unit disk
  std::vector<double> load;    // fraction of the normal load: area * shape / sum(area * shape)
  std::vector<double> shape;   // sqrt(1 - x^2 - y^2)
  std::vector<int> shape_index;  // of the cell's shape in `shapes`
  std::vector<double> shapes;  // the distinct shapes, in order of first appearance
  std::size_t count = 0;       // cells; x and y hold one more (0): a pair of cells read past the last
  [[nodiscard]] std::size_t cells() const { return count; }
};

// Column (or row) i of n over [-1, 1] as its mirror image with the larger centre: its bounds ((2 i -
// n) / n: the same bits for i and n - 1 - i) and the sign (+1, -1, 0 on the axis) of its centroid.
struct MirroredSpan {
  double lo, hi, sign;
};
MirroredSpan mirrored_span(int i, int n) {
  const int k = std::max(i, n - 1 - i);
  const double sign = 2 * i + 1 == n ? 0.0 : (k == i ? 1.0 : -1.0);
  return {static_cast<double>(2 * k - n) / n, static_cast<double>(2 * k + 2 - n) / n, sign};
}

std::unique_ptr<TractionGrid> build_grid(int gx, int gy) {
  auto grid = std::make_unique<TractionGrid>();
  grid->gx = gx;
  grid->gy = gy;
  const double cell_area = 4.0 / (static_cast<double>(gx) * gy);
  for (int i = 0; i < gx; ++i) {
    const MirroredSpan sx = mirrored_span(i, gx);
    for (int j = 0; j < gy; ++j) {
      const MirroredSpan sy = mirrored_span(j, gy);
      const Moments mo = disk_rectangle_moments(sx.lo, sx.hi, sy.lo, sy.hi);
      if (!(mo.area > 1e-14 * cell_area)) continue;
      const double x = sx.sign == 0 ? 0.0 : sx.sign * (mo.mx / mo.area);
      const double y = sy.sign == 0 ? 0.0 : sy.sign * (mo.my / mo.area);
      const double shape = std::sqrt(std::max(0.0, 1 - x * x - y * y));
      grid->x.push_back(x);
      grid->y.push_back(y);
      grid->area.push_back(mo.area);
      grid->shape.push_back(shape);
      grid->shape_integral += mo.area * shape;
    }
  }
  grid->count = grid->x.size();
  grid->x.push_back(0.0);
  grid->y.push_back(0.0);
  for (std::size_t i = 0; i < grid->cells(); ++i) {
    const double shape = grid->shape[i];
    grid->load.push_back(grid->area[i] * shape / grid->shape_integral);
    const auto same = std::find_if(grid->shapes.begin(), grid->shapes.end(), [&](double v) { return same_bits(v, shape); });
    grid->shape_index.push_back(static_cast<int>(same - grid->shapes.begin()));
    if (same == grid->shapes.end()) grid->shapes.push_back(shape);
  }
  return grid;
}

// Grids are built once per (grid_x, grid_y) and thread; a call allocates nothing after that.
const TractionGrid& traction_grid(int gx, int gy) {
  thread_local std::vector<std::unique_ptr<TractionGrid>> cache;
  thread_local const TractionGrid* last = nullptr;
  if (last != nullptr && last->gx == gx && last->gy == gy) return *last;
  for (const auto& g : cache)
    if (g->gx == gx && g->gy == gy) return *(last = g.get());
  cache.push_back(build_grid(gx, gy));
  return *(last = cache.back().get());
}

// tanh(x) / x, finite and smooth through x = 0 (even in x), to about an ulp (as std::tanh(x) / x)
// at a third of its cost: for |x| <= 1 the (8, 8) Pade approximant, the 8th convergent of Lambert's
// continued fraction tanh x = x / (1 + x^2 / (3 + x^2 / (5 + ...))) (truncation < 3e-17 at |x| = 1,
// positive coefficients: no cancellation), above it one exponential, tanh = 1 - 2 / (e^(2|x|) + 1)
// (no cancellation where tanh > 0.76), and 1 / |x| where tanh rounds to 1 (|x| > 19.06).
// pade_tanh_over_x(y) is the approximant at y = x^2 (for y <= 1), the same operations in the
// vectorised cell loop and here.
inline double pade_tanh_over_x(double y) {
  const double p = (((y + 990) * y + 135135) * y + 4729725) * y + 34459425;
  const double q = (((45 * y + 13860) * y + 945945) * y + 16216200) * y + 34459425;
  return p / q;
}
inline double tanh_over_x(double x) {
  const double y = x * x;
  if (y <= 1) return pade_tanh_over_x(y);
  const double a = std::abs(x);
  if (a > 19.5) return 1 / a;
  return (1 - 2 / (std::exp(2 * a) + 1)) / a;
}


// ---- the cell loop ---------------------------------------------------------------------------------

// A chunk of a block's cells: each cell's shear is -g (sx, sy) with g = a tanh_over_x(b s) (the
// film's shear: a = area eta / h, b = eta / (h tau_L); the curve: a = mu Q load / s_scale,
// b = 1 / s_scale), s the local sliding speed; the cell's terms of the four sums.
inline constexpr std::size_t chunk_cells = 64;  // even
struct CellChunk {
  std::array<double, chunk_cells> a, b;                // in: the coefficients
  std::array<double, chunk_cells> arg2;                // (b s)^2
  std::array<double, chunk_cells> fx, fy, mz, power;  // the cell's terms of the sums
};
// Where the chunk's cells are: their centroids (unit disk) and load fractions, from the chunk's
// first cell on; the ellipse's semi-axes and the contact's sliding.
struct ChunkCells {
  const double* x;
  const double* y;
  const double* load;
  double ax, ay;
  ContactSliding sliding;
};

// Every cell of the chunk by the approximant, without branches: the loop the compiler vectorises.
// `pairs` cells, an even number (a chunk with an odd number of cells takes one more, whose results
// are not summed), so that no scalar remainder is left.
void chunk_forces(CellChunk& __restrict c, std::size_t pairs, const double* __restrict gx,
                  const double* __restrict gy, double ax, double ay, const ContactSliding& sliding) {
  const double slide_x = sliding.slide_x, slide_y = sliding.slide_y, spin = sliding.spin;
  if (pairs % 2 != 0 || pairs > chunk_cells) __builtin_unreachable();
  for (std::size_t k = 0; k < pairs; ++k) {
    const double x = ax * gx[k], y = ay * gy[k];
    const double sx = slide_x - spin * y, sy = slide_y + spin * x;
    const double s2 = sx * sx + sy * sy, s = std::sqrt(s2);
    const double arg = c.b[k] * s, y2 = arg * arg;
    const double g = c.a[k] * pade_tanh_over_x(y2);
    const double cx = -g * sx, cy = -g * sy;
    c.arg2[k] = y2;
    c.fx[k] = cx, c.fy[k] = cy, c.mz[k] = x * cy - y * cx, c.power[k] = g * s2;
  }
}

// A cell beyond the approximant (b s > 1, or not a number), or one that blends in the friction
// curve (g = w g_film + curve_scale load tanh_over_x(s / s_scale)), again in scalar code: the
// cell's sliding as chunk_forces forms it, the same operations.
struct CurveBlend {
  bool on = false;
  double film_share = 1, curve_scale = 0, inverse_scale = 0;
};
void finish_cell(CellChunk& c, std::size_t k, const ChunkCells& in, const CurveBlend& curve) {
  const double x = in.ax * in.x[k], y = in.ay * in.y[k];
  const double sx = in.sliding.slide_x - in.sliding.spin * y, sy = in.sliding.slide_y + in.sliding.spin * x;
  const double s2 = sx * sx + sy * sy, s = std::sqrt(s2);
  double g = c.a[k] * tanh_over_x(c.b[k] * s);
  if (curve.on) g = curve.film_share * g + curve.curve_scale * in.load[k] * tanh_over_x(s * curve.inverse_scale);
  const double cx = -g * sx, cy = -g * sy;
  c.fx[k] = cx, c.fy[k] = cy, c.mz[k] = x * cy - y * cx, c.power[k] = g * s2;
}

}  // namespace

// ---- traction ------------------------------------------------------------------------------------

double film_weight(double film_thickness, const PointLubricant& lubricant) {
  if (!(film_thickness > 0)) return 0.0;
  if (!(film_thickness < lubricant.boundary_film)) return 1.0;
  const double x = film_thickness / lubricant.boundary_film;
  return x * x * (3 - 2 * x);
}

namespace {
int block_count(const TractionGrid& grid) {
  return static_cast<int>(std::clamp<std::size_t>(grid.cells() / traction_block_cells, 1, max_traction_blocks));
}
}  // namespace

int traction_block_count(const PointTraction& traction) {
  if (traction.grid_x < 1 || traction.grid_y < 1) return 1;
  return block_count(traction_grid(traction.grid_x, traction.grid_y));
}

namespace {

/// What the blocks of one contact's traction share: the checks, the grid, the scales and each
/// distinct shape's film shear (its viscosity's exponential), made once for all the blocks a caller
/// integrates (integrate_traction: both blocks of a 5 x 5 grid) and the same operations on the same
/// arguments whichever blocks follow, so every block has the bits it has alone.
class TractionCells {
 public:
  TractionCells(const PointTraction& traction, const PointLubricant& lubricant, double normal_force, double ax,
                double ay, double film_thickness, const ContactSliding& sliding)
      : lubricant_(lubricant), ax_(ax), ay_(ay), sliding_(sliding) {
    if (traction.model == TractionModel::none || !(normal_force > 0) || !(ax > 0) || !(ay > 0)) return;
    if (traction.grid_x < 1 || traction.grid_y < 1)
      throw std::invalid_argument("integrate_traction: grid_x and grid_y must be >= 1");
    limiting_ = traction.model == TractionModel::limiting_shear && film_thickness > 0 && lubricant.viscosity > 0;
    // Below the boundary film the film's shear (weight w) and the curve (1 - w) share the traction.
    const double film_share = limiting_ ? film_weight(film_thickness, lubricant) : 0.0;
    blended_ = limiting_ && film_share < 1;
    if (!limiting_ && traction.friction_coefficient == 0) return;
    active_ = true;
    grid_ = &traction_grid(traction.grid_x, traction.grid_y);
    area_scale_ = ax * ay;                                                      // unit disk -> ellipse
    pressure_scale_ = normal_force / (area_scale_ * grid_->shape_integral);  // ~ p_max
    const double mu_over_scale = traction.friction_coefficient / traction.slip_velocity_scale;
    inverse_scale_ = 1 / traction.slip_velocity_scale;
    inverse_h_ = limiting_ ? 1 / film_thickness : 0;
    curve_factor_ = mu_over_scale * normal_force;
    curve_ = CurveBlend{blended_, film_share, mu_over_scale * normal_force * (1 - film_share), inverse_scale_};
    shapes_ = limiting_ ? std::min(grid_->shapes.size(), max_distinct_shapes) : 0;
    for (std::size_t k = 0; k < shapes_; ++k) {
      const ShapeShear sh = shape_shear(grid_->shapes[k]);
      rate_[k] = sh.rate, slope_[k] = sh.slope;
    }
    tabulated_ = shapes_ == grid_->shapes.size();
  }

  /// Whether there is any traction to integrate (else every block is zero).
  [[nodiscard]] bool active() const { return active_; }
  [[nodiscard]] std::size_t cells() const { return grid_->cells(); }
  /// traction_block_count of the traction.
  [[nodiscard]] int blocks() const { return block_count(*grid_); }

  /// The sums over cells [first, last) in grid order (rows along x).
  TractionResult sum(std::size_t first, std::size_t last) {
    CellChunk c;  // NOLINT: filled for the first cells of each chunk
    double fx = 0, fy = 0, mz = 0, power = 0;
    const TractionGrid& grid = *grid_;
    for (std::size_t begin = first; begin < last; begin += chunk_cells) {
      const std::size_t n = std::min(chunk_cells, last - begin), pairs = n + n % 2;
      const double* area = grid.area.data() + begin;
      const int* index = grid.shape_index.data() + begin;
      if (!limiting_) {
        for (std::size_t k = 0; k < n; ++k) c.a[k] = curve_factor_ * grid.load[begin + k], c.b[k] = inverse_scale_;
      } else if (tabulated_) {
        for (std::size_t k = 0; k < n; ++k) {
          const auto si = static_cast<std::size_t>(index[k]);
          c.a[k] = rate_[si] * (area[k] * area_scale_), c.b[k] = slope_[si];
        }
      } else {
        for (std::size_t k = 0; k < n; ++k) {
          const auto si = static_cast<std::size_t>(index[k]);
          const ShapeShear sh = si < shapes_ ? ShapeShear{rate_[si], slope_[si]} : shape_shear(grid.shape[begin + k]);
          c.a[k] = sh.rate * (area[k] * area_scale_), c.b[k] = sh.slope;
        }
      }
      if (pairs > n) c.a[n] = c.b[n] = 0;
      const ChunkCells in{grid.x.data() + begin, grid.y.data() + begin, grid.load.data() + begin, ax_, ay_, sliding_};
      chunk_forces(c, pairs, in.x, in.y, ax_, ay_, sliding_);
      if (blended_)
        for (std::size_t k = 0; k < n; ++k) finish_cell(c, k, in, curve_);
      for (std::size_t k = 0; k < n; ++k) {  // cell by cell in grid order: the sums' bits
        if (!(c.arg2[k] <= 1) && !blended_) finish_cell(c, k, in, curve_);
        fx += c.fx[k];
        fy += c.fy[k];
        mz += c.mz[k];
        power += c.power[k];
      }
    }
    TractionResult out;
    out.force_x = fx;
    out.force_y = fy;
    out.spin_moment = mz;
    out.power_loss = power;
    return out;
  }

 private:
  // Per distinct shape (the first max_distinct_shapes, evaluated up front; a cell beyond them
  // evaluates its own): the film's shear rate factor eta / h and the tanh's argument per unit
  // sliding speed eta / (h tau_L), so that a cell takes g = area eta / h tanh_over_x(s eta / (h tau_L)).
  struct ShapeShear {
    double rate, slope;
  };
  ShapeShear shape_shear(double shape) {
    const double p = pressure_scale_ * shape;
    const double tau_limit = lubricant_.limiting_shear_coefficient * p;
    if (!(tau_limit > 0)) return ShapeShear{0, 0};
    const double rate = viscosity_at(p) * inverse_h_;
    return ShapeShear{rate, rate / tau_limit};
  }
  // Where the exponent reaches the cap (most of a loaded contact) the viscosity is one number,
  // evaluated once: std::min(exponent, cap) is the cap exactly when cap < exponent.
  double viscosity_at(double p) {
    const double cap = lubricant_.viscosity_exponent_cap;
    const double exponent = lubricant_.roelands_index > 0
                                ? roelands_exponent(lubricant_.viscosity, lubricant_.roelands_index, p)
                                : lubricant_.pressure_viscosity * p;
    if (!(cap < exponent)) return lubricant_.viscosity * std::exp(std::min(exponent, cap));
    if (!has_capped_) capped_viscosity_ = lubricant_.viscosity * std::exp(cap), has_capped_ = true;
    return capped_viscosity_;
  }

  const PointLubricant& lubricant_;
  double ax_, ay_;
  ContactSliding sliding_;
  bool active_ = false, limiting_ = false, blended_ = false, tabulated_ = false, has_capped_ = false;
  const TractionGrid* grid_ = nullptr;
  double area_scale_ = 0, pressure_scale_ = 0, inverse_scale_ = 0, inverse_h_ = 0, curve_factor_ = 0;
  double capped_viscosity_ = std::numeric_limits<double>::quiet_NaN();
  CurveBlend curve_;
  std::size_t shapes_ = 0;
  std::array<double, max_distinct_shapes> rate_, slope_;  // NOLINT: the first shapes_ are set
};

/// Block b of `blocks`: cells [n b / blocks, n (b + 1) / blocks) in grid order (rows along x).
TractionResult block_sum(TractionCells& cells, std::size_t b, std::size_t blocks) {
  return cells.sum(cells.cells() * b / blocks, cells.cells() * (b + 1) / blocks);
}

}  // namespace

TractionResult integrate_traction_block(const PointTraction& traction, const PointLubricant& lubricant,
                                        double normal_force, double ax, double ay, double film_thickness,
                                        const ContactSliding& sliding, int block) {
  TractionCells cells(traction, lubricant, normal_force, ax, ay, film_thickness, sliding);
  if (!cells.active()) return {};
  const auto blocks = static_cast<std::size_t>(cells.blocks());
  const auto b = static_cast<std::size_t>(block);
  if (block < 0 || b >= blocks) throw std::invalid_argument("integrate_traction_block: no such block");
  return block_sum(cells, b, blocks);
}

TractionResult sum_traction_blocks(std::span<const TractionResult> blocks) {
  if (blocks.empty()) return {};
  TractionResult sum = blocks[0];
  for (std::size_t b = 1; b < blocks.size(); ++b) {
    sum.force_x += blocks[b].force_x;
    sum.force_y += blocks[b].force_y;
    sum.spin_moment += blocks[b].spin_moment;
    sum.power_loss += blocks[b].power_loss;
  }
  return sum;
}

TractionResult integrate_traction(const PointTraction& traction, const PointLubricant& lubricant,
                                  double normal_force, double ax, double ay, double film_thickness,
                                  const ContactSliding& sliding) {
  // The blocks' shared part once (TractionCells), then each block's sums as integrate_traction_block
  // forms them, added in block order: the bits of the blocks evaluated as tasks of their own.
  TractionCells cells(traction, lubricant, normal_force, ax, ay, film_thickness, sliding);
  if (!cells.active()) return {};
  const int blocks = cells.blocks();
  if (blocks == 1) return block_sum(cells, 0, 1);
  std::array<TractionResult, max_traction_blocks> partial{};
  const int n = std::min(blocks, max_traction_blocks);
  for (int b = 0; b < n; ++b)
    partial[static_cast<std::size_t>(b)] = block_sum(cells, static_cast<std::size_t>(b), static_cast<std::size_t>(blocks));
  return sum_traction_blocks(std::span<const TractionResult>(partial.data(), static_cast<std::size_t>(n)));
}

}  // namespace raceway::contact
