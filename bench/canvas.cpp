#include "bench/canvas.h"

#include "bench/metrics.h"
#include "renderer/core/image_io.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace deepgi::bench {

namespace {

// 5x7 glyphs, one byte per row, bit 4 = leftmost column.
struct Glyph {
    char c;
    uint8_t rows[7];
};
const Glyph kFont[] = {
    {'A', {0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}}, {'B', {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E}},
    {'C', {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}}, {'D', {0x1E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1E}},
    {'E', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}}, {'F', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10}},
    {'G', {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}}, {'H', {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
    {'I', {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}}, {'J', {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C}},
    {'K', {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}}, {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F}},
    {'M', {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}}, {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}},
    {'O', {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}}, {'P', {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10}},
    {'Q', {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}}, {'R', {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11}},
    {'S', {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}}, {'T', {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
    {'U', {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}}, {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04}},
    {'W', {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}}, {'X', {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11}},
    {'Y', {0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04}}, {'Z', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F}},
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}}, {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}}, {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}}, {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}}, {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}}, {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}}, {',', {0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08}},
    {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}}, {'_', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F}},
    {'=', {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}}, {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}},
    {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}}, {'/', {0x01, 0x01, 0x02, 0x04, 0x08, 0x10, 0x10}},
    {':', {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}}, {'%', {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}},
    {'+', {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}}, {'<', {0x02, 0x04, 0x08, 0x10, 0x08, 0x04, 0x02}},
    {'>', {0x08, 0x04, 0x02, 0x01, 0x02, 0x04, 0x08}}, {'|', {0x04, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
};

const Glyph* findGlyph(char c) {
    c = char(std::toupper((unsigned char)c));
    for (const Glyph& g : kFont)
        if (g.c == c) return &g;
    return nullptr;
}

// A "nice" axis maximum (1, 2 or 5 times a power of ten) at or above v, and its tick step.
void niceAxis(double v, double& max, double& step) {
    if (!(v > 0.0) || !std::isfinite(v)) v = 1.0;
    const double p = std::pow(10.0, std::floor(std::log10(v)));
    max = 10.0 * p;
    for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
        if (m * p >= v) {
            max = m * p;
            break;
        }
    step = max / 5.0;
}

std::string tickLabel(double v) {
    char buf[32];
    if (v == 0.0) return "0";
    if (std::abs(v) >= 100) std::snprintf(buf, sizeof buf, "%.0f", v);
    else if (std::abs(v) >= 1) std::snprintf(buf, sizeof buf, "%.1f", v);
    else std::snprintf(buf, sizeof buf, "%.2f", v);
    return buf;
}

}  // namespace

Canvas::Canvas(int width, int height, Rgb bg) : w_(std::max(1, width)), h_(std::max(1, height)) {
    px_.resize(size_t(w_) * h_ * 3);
    for (size_t i = 0; i < size_t(w_) * h_; ++i) {
        px_[i * 3] = bg.r;
        px_[i * 3 + 1] = bg.g;
        px_[i * 3 + 2] = bg.b;
    }
}

void Canvas::set(int x, int y, Rgb c) {
    if (x < 0 || y < 0 || x >= w_ || y >= h_) return;
    unsigned char* p = &px_[(size_t(y) * w_ + x) * 3];
    p[0] = c.r;
    p[1] = c.g;
    p[2] = c.b;
}

Rgb Canvas::get(int x, int y) const {
    if (x < 0 || y < 0 || x >= w_ || y >= h_) return {0, 0, 0};
    const unsigned char* p = &px_[(size_t(y) * w_ + x) * 3];
    return {p[0], p[1], p[2]};
}

void Canvas::fillRect(int x0, int y0, int x1, int y1, Rgb c) {
    for (int y = std::max(0, y0); y < std::min(h_, y1); ++y)
        for (int x = std::max(0, x0); x < std::min(w_, x1); ++x) set(x, y, c);
}

void Canvas::line(int x0, int y0, int x1, int y1, Rgb c, int thickness) {
    const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
    const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
    int err = dx + dy;
    const int r0 = -(thickness - 1) / 2, r1 = thickness / 2;
    for (;;) {
        for (int oy = r0; oy <= r1; ++oy)
            for (int ox = r0; ox <= r1; ++ox) set(x0 + ox, y0 + oy, c);
        if (x0 == x1 && y0 == y1) break;
        const int e2 = 2 * err;
        if (e2 >= dy) {
            err += dy;
            x0 += sx;
        }
        if (e2 <= dx) {
            err += dx;
            y0 += sy;
        }
    }
}

void Canvas::disc(int cx, int cy, int r, Rgb c) {
    for (int y = -r; y <= r; ++y)
        for (int x = -r; x <= r; ++x)
            if (x * x + y * y <= r * r) set(cx + x, cy + y, c);
}

void Canvas::ring(int cx, int cy, int r, Rgb c) {
    for (int y = -r - 1; y <= r + 1; ++y)
        for (int x = -r - 1; x <= r + 1; ++x) {
            const int d2 = x * x + y * y;
            if (d2 <= (r + 1) * (r + 1) && d2 >= (r - 1) * (r - 1)) set(cx + x, cy + y, c);
        }
}

int Canvas::text(int x, int y, const std::string& s, Rgb c, int scale) {
    int pen = x;
    for (char ch : s) {
        if (const Glyph* g = findGlyph(ch))
            for (int row = 0; row < 7; ++row)
                for (int col = 0; col < 5; ++col)
                    if (g->rows[row] & (0x10 >> col)) fillRect(pen + col * scale, y + row * scale, pen + (col + 1) * scale, y + (row + 1) * scale, c);
        pen += 6 * scale;
    }
    return pen - x;
}

void Canvas::blit(int x, int y, int w, int h, int channels, const std::vector<unsigned char>& px) {
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const unsigned char* p = &px[(size_t(j) * w + i) * channels];
            set(x + i, y + j, {p[0], p[1], p[2]});
        }
}

void Canvas::savePng(const std::string& path) const { writePng8(path, w_, h_, 3, px_); }

Rgb heat(double t) {
    t = std::clamp(std::isfinite(t) ? t : 1.0, 0.0, 1.0);
    static const double stops[5][3] = {{0, 0, 0}, {80, 20, 130}, {220, 60, 60}, {250, 170, 30}, {255, 255, 160}};
    const double f = t * 4.0;
    const int i = std::min(3, int(f));
    const double u = f - i;
    auto mix = [&](int c) { return uint8_t(std::lround(stops[i][c] + (stops[i + 1][c] - stops[i][c]) * u)); };
    return {mix(0), mix(1), mix(2)};
}

Canvas speedErrorPlot(const std::vector<PlotSeries>& series, const std::string& title, const std::string& xLabel,
                      const std::string& yLabel, int width, int height) {
    Canvas cv(width, height);
    const int left = 70, right = 20, top = 40, bottom = 60;
    const int pw = width - left - right, ph = height - top - bottom;
    double xmaxData = 0.0, ymaxData = 0.0;
    for (const auto& s : series)
        for (size_t i = 0; i < s.x.size(); ++i) {
            if (std::isfinite(s.x[i])) xmaxData = std::max(xmaxData, s.x[i]);
            if (std::isfinite(s.y[i])) ymaxData = std::max(ymaxData, s.y[i]);
        }
    double xmax = 1.0, xstep = 0.2, ymax = 1.0, ystep = 0.2;
    niceAxis(xmaxData * 1.05, xmax, xstep);
    niceAxis(ymaxData * 1.05, ymax, ystep);
    auto X = [&](double v) { return left + int(std::lround(v / xmax * pw)); };
    auto Y = [&](double v) { return top + ph - int(std::lround(v / ymax * ph)); };
    const Rgb black{0, 0, 0}, grid{225, 225, 225};
    for (int k = 0; k <= 5; ++k) {
        const double xv = k * xstep, yv = k * ystep;
        cv.line(X(xv), top, X(xv), top + ph, grid);
        cv.line(left, Y(yv), left + pw, Y(yv), grid);
        const std::string xl = tickLabel(xv), yl = tickLabel(yv);
        cv.text(X(xv) - Canvas::textWidth(xl) / 2, top + ph + 6, xl, black);
        cv.text(left - 6 - Canvas::textWidth(yl), Y(yv) - 3, yl, black);
    }
    cv.line(left, top, left, top + ph, black);
    cv.line(left, top + ph, left + pw, top + ph, black);
    cv.text(left + pw / 2 - Canvas::textWidth(xLabel) / 2, top + ph + 22, xLabel, black);
    cv.text(8, top - 16, yLabel, black);
    cv.text(width / 2 - Canvas::textWidth(title, 2) / 2, 8, title, black, 2);
    int legendY = top + 6;
    for (const auto& s : series) {
        cv.disc(left + pw - 160, legendY + 3, 3, s.color);
        cv.text(left + pw - 150, legendY, s.name, black);
        legendY += 12;
    }
    cv.text(left + pw - 160, legendY + 2, "line+ring = pareto front", black);
    for (const auto& s : series) {
        std::vector<Point2> pts;
        for (size_t i = 0; i < s.x.size(); ++i) pts.push_back({s.x[i], s.y[i]});
        const std::vector<int> front = paretoFront(pts);
        for (size_t k = 1; k < front.size(); ++k)
            cv.line(X(s.x[front[k - 1]]), Y(s.y[front[k - 1]]), X(s.x[front[k]]), Y(s.y[front[k]]), s.color, 2);
        for (size_t i = 0; i < s.x.size(); ++i)
            if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) cv.disc(X(s.x[i]), Y(s.y[i]), 3, s.color);
        for (int i : front) {
            cv.ring(X(s.x[i]), Y(s.y[i]), 6, black);
            if (size_t(i) < s.labels.size()) cv.text(X(s.x[i]) + 8, Y(s.y[i]) - 10, s.labels[i], s.color);
        }
    }
    return cv;
}

}  // namespace deepgi::bench
