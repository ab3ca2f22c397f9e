/* Fast-Hessian detector (Bay et al. 2008, section 3). Private to CSurf. */
#include "surf_FastHessian.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <opencv2/core/utility.hpp>
#include <optional>

namespace roislam::features::surf
{
int filterSize(int octave, int layer, int nOctaveLayers)
{
  int first = 9;
  for (int o = 0; o < octave; ++o)
    first += (nOctaveLayers - 1) * (6 << o);
  return first + layer * (6 << octave);
}

namespace
{
/** Relative weight of Dxy in the determinant (paper eq. 4: w ~ 0.9). */
constexpr float kDxyWeight = 0.9f;

/** A box over pixel rows/cols [x0, x1] x [y0, y1] (inclusive, relative to the
 *  filter centre) as four offsets into the integral image. */
struct TBox
{
  int o00 = 0, o01 = 0, o10 = 0, o11 = 0;

  TBox() = default;
  TBox(int x0, int y0, int x1, int y1, int stride)
      : o00(y0 * stride + x0),
        o01(y0 * stride + x1 + 1),
        o10((y1 + 1) * stride + x0),
        o11((y1 + 1) * stride + x1 + 1)
  {
  }
  int sum(const int32_t* p) const { return p[o11] - p[o01] - p[o10] + p[o00]; }
};

/** Half-extent across the derivative direction of the Dxx / Dyy lobes of a
 *  filter of side L: the paper's 9x9 filter has lobes 5 pixels wide, i.e.
 *  5/9 of L, and larger filters are that filter scaled up. (Widening the lobes
 *  by 2 pixels per 6 of L, i.e. 2 * lobe - 1 = 2/3 of L for large filters,
 *  makes Dxx / Dyy wider than Dxy: the box Hessian is then no longer
 *  consistent, its determinant depends on the image orientation and coarse
 *  keypoints moved by several pixels under rotation.) The width is kept odd
 *  so that the filter stays centred on a pixel. */
int crossHalfExtent(int L)
{
  return static_cast<int>(std::lround((5.0 * L / 9.0 - 1.0) / 2.0));
}

/** The three box filters of one filter size L = 3 * lobe (lobe odd). Dxx is
 *  the whole 3-lobe region minus 3x its middle lobe (weights 1, -2, 1), each
 *  lobe 2 * crossHalfExtent(L) + 1 tall; Dxy the four lobe x lobe squares
 *  around the centre. Responses are normalised by the filter area L^2 (paper,
 *  section 3.3), which is what OpenCV's SURF hessianThreshold refers to. With
 *  the paper's proportions at every size the Frobenius-norm balance of Dxy
 *  against Dxx (paper eq. 4) stays at its 9x9 value, so w is constant. */
struct TFilter
{
  int L = 0, border = 0;
  TBox xxAll, xxMid, yyAll, yyMid, xy[4];
  float norm = 0;

  TFilter(int size, int stride) : L(size), border((size - 1) / 2)
  {
    const int lobe = size / 3, h = (lobe - 1) / 2, b = border, q = crossHalfExtent(size);
    xxAll = TBox(-b, -q, b, q, stride);
    xxMid = TBox(-h, -q, h, q, stride);
    yyAll = TBox(-q, -b, q, b, stride);
    yyMid = TBox(-q, -h, q, h, stride);
    xy[0] = TBox(-lobe, -lobe, -1, -1, stride);  // weight +1
    xy[1] = TBox(1, -lobe, lobe, -1, stride);    // -1
    xy[2] = TBox(-lobe, 1, -1, lobe, stride);    // -1
    xy[3] = TBox(1, 1, lobe, lobe, stride);      // +1
    norm = 1.0f / (static_cast<float>(size) * static_cast<float>(size));
  }

  /** Box-filter Hessian determinant (paper eq. 4) at corner p. */
  float det(const int32_t* p) const
  {
    float dxx, dyy, dxy;
    responses(p, dxx, dyy, dxy);
    const float w = kDxyWeight * dxy;
    return dxx * dyy - w * w;
  }

  /** Normalised Dxx, Dyy, Dxy at the pixel whose integral-image corner is p. */
  void responses(const int32_t* p, float& dxx, float& dyy, float& dxy) const
  {
    dxx = static_cast<float>(xxAll.sum(p) - 3 * xxMid.sum(p)) * norm;
    dyy = static_cast<float>(yyAll.sum(p) - 3 * yyMid.sum(p)) * norm;
    dxy = static_cast<float>(xy[0].sum(p) - xy[1].sum(p) - xy[2].sum(p) + xy[3].sum(p)) * norm;
  }
};

/** Determinant and Laplacian sign of one filter size on the sampling grid of
 *  an octave; cells where the filter does not fit are 0. */
struct TLayer
{
  int L = 0, border = 0;
  std::vector<float> det;
  std::vector<int8_t> sign;
};

/** First and last grid index (inclusive) at which a filter with this border
 *  fits inside [0, extent-1] when sampling every `step` pixels. */
std::pair<int, int> validRange(int border, int extent, int step)
{
  return {(border + step - 1) / step, (extent - 1 - border) / step};
}

/** Determinant and Laplacian sign along one grid row. Offsets are copied to
 *  locals and outputs are restrict-qualified so that, with unit stride, the
 *  compiler vectorises the loop (int8 stores could otherwise alias the filter). */
template <int kUnitStride>
void rowResponses(
    const int32_t* __restrict base, int step, int count, const TFilter& f, float* __restrict det,
    int8_t* __restrict sign)
{
  const int a00 = f.xxAll.o00, a01 = f.xxAll.o01, a10 = f.xxAll.o10, a11 = f.xxAll.o11;
  const int b00 = f.xxMid.o00, b01 = f.xxMid.o01, b10 = f.xxMid.o10, b11 = f.xxMid.o11;
  const int c00 = f.yyAll.o00, c01 = f.yyAll.o01, c10 = f.yyAll.o10, c11 = f.yyAll.o11;
  const int d00 = f.yyMid.o00, d01 = f.yyMid.o01, d10 = f.yyMid.o10, d11 = f.yyMid.o11;
  const TBox q0 = f.xy[0], q1 = f.xy[1], q2 = f.xy[2], q3 = f.xy[3];
  const float norm = f.norm, w2 = kDxyWeight * kDxyWeight * f.norm * f.norm;
  for (int j = 0; j < count; ++j)
  {
    const int32_t* p = base + (kUnitStride ? j : j * step);
    const int xx = (p[a11] - p[a01] - p[a10] + p[a00]) - 3 * (p[b11] - p[b01] - p[b10] + p[b00]);
    const int yy = (p[c11] - p[c01] - p[c10] + p[c00]) - 3 * (p[d11] - p[d01] - p[d10] + p[d00]);
    const int xy = (p[q0.o11] - p[q0.o01] - p[q0.o10] + p[q0.o00]) -
                   (p[q1.o11] - p[q1.o01] - p[q1.o10] + p[q1.o00]) -
                   (p[q2.o11] - p[q2.o01] - p[q2.o10] + p[q2.o00]) +
                   (p[q3.o11] - p[q3.o01] - p[q3.o10] + p[q3.o00]);
    const float dxx = static_cast<float>(xx) * norm, dyy = static_cast<float>(yy) * norm;
    const float fxy = static_cast<float>(xy);
    det[j] = dxx * dyy - w2 * fxy * fxy;
    sign[j] = (xx + yy) > 0 ? 1 : -1;
  }
}

void computeLayers(const TIntegral& in, int step, int nx, int ny, std::vector<TLayer>& layers)
{
  const int nLayers = static_cast<int>(layers.size());
  std::vector<TFilter> filters;
  for (const auto& l : layers)
    filters.emplace_back(l.L, in.stride);
  // One task per (layer, row): rows of different layers have different cost,
  // the fine granularity keeps both cores busy.
  cv::parallel_for_(
      cv::Range(0, nLayers * ny),
      [&](const cv::Range& r)
      {
        for (int t = r.start; t < r.end; ++t)
        {
          const int li = t / ny, i = t % ny;
          TLayer& layer = layers[li];
          const TFilter& f = filters[li];
          float* det = layer.det.data() + static_cast<size_t>(i) * nx;
          int8_t* sign = layer.sign.data() + static_cast<size_t>(i) * nx;
          std::fill(det, det + nx, 0.0f);
          std::fill(sign, sign + nx, int8_t(0));
          const auto [i0, i1] = validRange(f.border, in.rows, step);
          if (i < i0 || i > i1)
            continue;
          const auto [j0, j1] = validRange(f.border, in.cols, step);
          const int y = i * step;
          const int32_t* row = in.data + y * in.stride;
          if (step == 1)
            rowResponses<1>(row + j0, 1, j1 - j0 + 1, f, det + j0, sign + j0);
          else
            rowResponses<0>(row + j0 * step, step, j1 - j0 + 1, f, det + j0, sign + j0);
        }
      });
}

/** Solves the 3x3 system H x = -g (quadratic fit, Brown & Lowe) by Cramer's
 *  rule; false when H is singular. */
bool solve3(const float H[3][3], const float g[3], float x[3])
{
  const double a = H[0][0], b = H[0][1], c = H[0][2], d = H[1][0], e = H[1][1], f = H[1][2],
               gg = H[2][0], h = H[2][1], k = H[2][2];
  const double det = a * (e * k - f * h) - b * (d * k - f * gg) + c * (d * h - e * gg);
  if (std::abs(det) < 1e-12)
    return false;
  const double r0 = -g[0], r1 = -g[1], r2 = -g[2];
  x[0] = static_cast<float>(
      (r0 * (e * k - f * h) - b * (r1 * k - f * r2) + c * (r1 * h - e * r2)) / det);
  x[1] = static_cast<float>(
      (a * (r1 * k - f * r2) - r0 * (d * k - f * gg) + c * (d * r2 - r1 * gg)) / det);
  x[2] = static_cast<float>(
      (a * (e * r2 - r1 * h) - b * (d * r2 - r1 * gg) + r0 * (d * h - e * gg)) / det);
  return true;
}

/** One octave's search: its stored layers 1..n (computeLayers) and, on
 *  demand, the outer layers 0 and n+1, which only serve as neighbours of
 *  candidates (a few thousand 3x3 patches instead of every grid cell). */
class COctaveSearch
{
 public:
  COctaveSearch(const TIntegral& in, int octave, int nOctaveLayers, std::vector<TLayer>& layers)
      : m_in(in),
        m_o(octave),
        m_n(nOctaveLayers),
        m_step(1 << octave),
        m_nx((in.cols - 1) / m_step + 1),
        m_ny((in.rows - 1) / m_step + 1),
        m_layers(layers),
        m_below(filterSize(octave, 0, nOctaveLayers), in.stride),
        m_above(filterSize(octave, nOctaveLayers + 1, nOctaveLayers), in.stride)
  {
    for (int l = 0; l < m_n; ++l)
    {
      m_layers[l].L = filterSize(m_o, l + 1, m_n);
      m_layers[l].border = (m_layers[l].L - 1) / 2;
      m_layers[l].det.resize(static_cast<size_t>(m_nx) * m_ny);
      m_layers[l].sign.resize(static_cast<size_t>(m_nx) * m_ny);
    }
    computeLayers(m_in, m_step, m_nx, m_ny, m_layers);
  }

  /** Rows searched per stored layer (the outermost rows have no 3x3). */
  int rowsPerLayer() const { return std::max(0, m_ny - 2); }

  /** Keypoints on row 1 + t % rowsPerLayer() of stored layer t / rowsPerLayer(). */
  void searchRow(int t, float threshold, std::vector<cv::KeyPoint>& out) const
  {
    const int l = t / rowsPerLayer(), i = 1 + t % rowsPerLayer();
    // The 3x3 neighbourhood must be valid in the layer above too.
    const int borderAbove = (filterSize(m_o, l + 2, m_n) - 1) / 2;
    const auto [i0, i1] = validRange(borderAbove, m_in.rows, m_step);
    if (i <= i0 || i >= i1)
      return;
    const auto [j0, j1] = validRange(borderAbove, m_in.cols, m_step);
    const float* Dc = m_layers[l].det.data();
    for (int j = j0 + 1; j <= j1 - 1; ++j)
    {
      const size_t c = static_cast<size_t>(i) * m_nx + j;
      const float v = Dc[c];
      if (v <= threshold || !maximumInLayer(Dc, c, v) || !maximumAcrossLayers(l, i, j, c, v))
        continue;
      if (auto kp = refine(l + 1, i, j))
      {
        kp->octave = m_o;
        out.push_back(*kp);
      }
    }
  }

 private:
  /** The cheap test first: v is the maximum of its 3x3 in its own layer. */
  bool maximumInLayer(const float* Dc, size_t c, float v) const
  {
    const int nx = m_nx;
    return !(
        Dc[c - 1] >= v || Dc[c + 1] >= v || Dc[c - nx - 1] >= v || Dc[c - nx] >= v ||
        Dc[c - nx + 1] >= v || Dc[c + nx - 1] >= v || Dc[c + nx] >= v || Dc[c + nx + 1] >= v);
  }

  /** v is above the 3x3 neighbourhoods of the layers below and above. */
  bool maximumAcrossLayers(int l, int i, int j, size_t c, float v) const
  {
    const int32_t* row = m_in.data + i * m_step * m_in.stride;
    for (int di = -1; di <= 1; ++di)
      for (int dj = -1; dj <= 1; ++dj)
      {
        const ptrdiff_t q = static_cast<ptrdiff_t>(c) + di * m_nx + dj;
        const int32_t* p = row + di * m_step * m_in.stride + (j + dj) * m_step;
        const float b = l > 0 ? m_layers[l - 1].det[q] : m_below.det(p);
        const float a = l < m_n - 1 ? m_layers[l + 1].det[q] : m_above.det(p);
        if (b >= v || a >= v)
          return false;
      }
    return true;
  }

  /** Determinant at grid cell (i, j) of octave layer ly (0 .. n+1). */
  float detAt(int ly, int i, int j) const
  {
    if (ly >= 1 && ly <= m_n)
      return m_layers[ly - 1].det[static_cast<size_t>(i) * m_nx + j];
    return (ly == 0 ? m_below : m_above).det(m_in.data + i * m_step * m_in.stride + j * m_step);
  }

  /** Sub-pixel / sub-scale position by fitting a 3-D quadratic to the
   *  determinant (Brown & Lowe, as the paper does). An offset of up to one
   *  cell is accepted (measured on fr1/rpy: requiring half a cell and moving
   *  to the neighbour lost keypoints without making the rest more
   *  repeatable); a larger one is refitted around the neighbouring cell, at
   *  most 5 times. */
  std::optional<cv::KeyPoint> refine(int ly, int i, int j) const
  {
    for (int iter = 0; iter < 5; ++iter)
    {
      const int borderAbove = (filterSize(m_o, ly + 1, m_n) - 1) / 2;
      const auto [i0, i1] = validRange(borderAbove, m_in.rows, m_step);
      const auto [j0, j1] = validRange(borderAbove, m_in.cols, m_step);
      if (ly < 1 || ly > m_n || i <= i0 || i >= i1 || j <= j0 || j >= j1)
        return std::nullopt;
      float g[3], H[3][3], x[3];
      const float v = fitQuadratic(ly, i, j, g, H);
      if (!solve3(H, g, x))
        return std::nullopt;
      if (std::abs(x[0]) <= 1.0f && std::abs(x[1]) <= 1.0f && std::abs(x[2]) <= 1.0f)
      {
        cv::KeyPoint kp;
        kp.pt = cv::Point2f((j + x[0]) * m_step, (i + x[1]) * m_step);
        const float dL = static_cast<float>(6 << m_o);  // filter size step in this octave
        kp.size = static_cast<float>(filterSize(m_o, ly, m_n)) + x[2] * dL;
        kp.response = v + 0.5f * (g[0] * x[0] + g[1] * x[1] + g[2] * x[2]);
        kp.angle = -1;
        kp.class_id = m_layers[ly - 1].sign[static_cast<size_t>(i) * m_nx + j];
        return kp;
      }
      // Offsets of several cells mean the quadratic model does not hold.
      if (std::abs(x[0]) > 2.0f || std::abs(x[1]) > 2.0f || std::abs(x[2]) > 2.0f)
        return std::nullopt;
      j += static_cast<int>(std::lround(x[0]));
      i += static_cast<int>(std::lround(x[1]));
      ly += static_cast<int>(std::lround(x[2]));
    }
    return std::nullopt;
  }

  /** Gradient g and Hessian H of the determinant at (ly, i, j) by central
   *  differences over (x, y, scale); returns the determinant there. */
  float fitQuadratic(int ly, int i, int j, float g[3], float H[3][3]) const
  {
    const float v = detAt(ly, i, j);
    const float xp = detAt(ly, i, j + 1), xm = detAt(ly, i, j - 1);
    const float yp = detAt(ly, i + 1, j), ym = detAt(ly, i - 1, j);
    const float sp = detAt(ly + 1, i, j), sm = detAt(ly - 1, i, j);
    g[0] = 0.5f * (xp - xm);
    g[1] = 0.5f * (yp - ym);
    g[2] = 0.5f * (sp - sm);
    H[0][0] = xp + xm - 2 * v;
    H[1][1] = yp + ym - 2 * v;
    H[2][2] = sp + sm - 2 * v;
    H[0][1] = H[1][0] = 0.25f * (detAt(ly, i + 1, j + 1) - detAt(ly, i + 1, j - 1) -
                                 detAt(ly, i - 1, j + 1) + detAt(ly, i - 1, j - 1));
    H[0][2] = H[2][0] = 0.25f * (detAt(ly + 1, i, j + 1) - detAt(ly + 1, i, j - 1) -
                                 detAt(ly - 1, i, j + 1) + detAt(ly - 1, i, j - 1));
    H[1][2] = H[2][1] = 0.25f * (detAt(ly + 1, i + 1, j) - detAt(ly + 1, i - 1, j) -
                                 detAt(ly - 1, i + 1, j) + detAt(ly - 1, i - 1, j));
    return v;
  }

  const TIntegral& m_in;
  const int m_o, m_n, m_step, m_nx, m_ny;
  std::vector<TLayer>& m_layers;
  const TFilter m_below, m_above;
};
}  // namespace

std::vector<cv::KeyPoint> detectFastHessian(const TIntegral& in, const TFastHessianParams& prm)
{
  std::vector<cv::KeyPoint> out;
  const int n = prm.nOctaveLayers;
  const float thr = static_cast<float>(prm.threshold);
  std::vector<TLayer> layers(n);
  for (int o = 0; o < prm.nOctaves; ++o)
  {
    const int largest = filterSize(o, n + 1, n);
    if (largest > in.rows || largest > in.cols)
      break;  // octave does not fit
    const COctaveSearch octave(in, o, n, layers);
    // One task per (searched layer, row); results per task keep the order
    // deterministic whatever the scheduling.
    const int tasks = n * octave.rowsPerLayer();
    std::vector<std::vector<cv::KeyPoint>> found(static_cast<size_t>(tasks));
    cv::parallel_for_(
        cv::Range(0, tasks),
        [&](const cv::Range& r)
        {
          for (int t = r.start; t < r.end; ++t)
            octave.searchRow(t, thr, found[t]);
        });
    for (const auto& f : found)
      out.insert(out.end(), f.begin(), f.end());
  }
  return out;
}

int laplacianSign(const TIntegral& in, const cv::KeyPoint& kp)
{
  int lobe = std::max(3, static_cast<int>(std::lround(kp.size / 3.0f)));
  if (lobe % 2 == 0)
    ++lobe;
  const int L = 3 * lobe, b = (L - 1) / 2, h = (lobe - 1) / 2, q = crossHalfExtent(L);
  const int x = static_cast<int>(std::lround(kp.pt.x)), y = static_cast<int>(std::lround(kp.pt.y));
  // Clamped sums: keypoints from other detectors may lie near the border.
  const auto box = [&](int x0, int y0, int x1, int y1)
  { return in.boxClamped(x + x0, y + y0, x + x1 + 1, y + y1 + 1); };
  const int dxx = box(-b, -q, b, q) - 3 * box(-h, -q, h, q);
  const int dyy = box(-q, -b, q, b) - 3 * box(-q, -h, q, h);
  return (dxx + dyy) > 0 ? 1 : -1;
}
}  // namespace roislam::features::surf
