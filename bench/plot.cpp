#include "bench/plot.h"

#include "bench/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace deepgi::bench {

namespace {

std::string tickLabel(double v) {
    char buf[32];
    if (v == 0.0) return "0";
    if (std::abs(v) >= 100) std::snprintf(buf, sizeof buf, "%.0f", v);
    else if (std::abs(v) >= 1) std::snprintf(buf, sizeof buf, "%.1f", v);
    else std::snprintf(buf, sizeof buf, "%.2f", v);
    return buf;
}

void marker(OIIO::ImageBuf& img, int x, int y, int r, draw::Colour c, bool fill) { draw::box(img, x - r, y - r, x + r, y + r, c, fill); }

}  // namespace

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

OIIO::ImageBuf speedErrorPlot(const std::vector<PlotSeries>& series, const std::string& title, const std::string& xLabel,
                              const std::string& yLabel, int width, int height) {
    OIIO::ImageBuf img = draw::canvas(width, height);
    const int left = 70, right = 20, top = 40, bottom = 60;
    const int pw = width - left - right, ph = height - top - bottom;
    double xmaxData = 0.0, ymaxData = 0.0;
    for (const auto& s : series)
        for (size_t i = 0; i < s.x.size(); ++i) {
            if (std::isfinite(s.x[i])) xmaxData = std::max(xmaxData, s.x[i]);
            if (std::isfinite(s.y[i])) ymaxData = std::max(ymaxData, s.y[i]);
        }
    double xmax, xstep, ymax, ystep;
    niceAxis(xmaxData * 1.05, xmax, xstep);
    niceAxis(ymaxData * 1.05, ymax, ystep);
    auto X = [&](double v) { return left + int(std::lround(v / xmax * pw)); };
    auto Y = [&](double v) { return top + ph - int(std::lround(v / ymax * ph)); };
    const draw::Colour black{0, 0, 0}, grid{0.88f, 0.88f, 0.88f};
    for (int k = 0; k <= 5; ++k) {
        const double xv = k * xstep, yv = k * ystep;
        draw::line(img, X(xv), top, X(xv), top + ph, grid);
        draw::line(img, left, Y(yv), left + pw, Y(yv), grid);
        const std::string xl = tickLabel(xv), yl = tickLabel(yv);
        draw::text(img, X(xv) - draw::textWidth(xl) / 2, top + ph + 4, xl, black);
        draw::text(img, left - 6 - draw::textWidth(yl), Y(yv) - 7, yl, black);
    }
    draw::line(img, left, top, left, top + ph, black);
    draw::line(img, left, top + ph, left + pw, top + ph, black);
    draw::text(img, left + pw / 2 - draw::textWidth(xLabel) / 2, top + ph + 22, xLabel, black);
    draw::text(img, 8, top - 18, yLabel, black);
    draw::text(img, width / 2 - draw::textWidth(title, 18) / 2, 4, title, black, 18);
    int legendY = top + 6;
    for (const auto& s : series) {
        marker(img, left + pw - 200, legendY + 7, 3, s.color, true);
        draw::text(img, left + pw - 190, legendY, s.name, black);
        legendY += 15;
    }
    draw::text(img, left + pw - 200, legendY + 2, "line + box = Pareto front", black);
    for (const auto& s : series) {
        std::vector<Point2> pts;
        for (size_t i = 0; i < s.x.size(); ++i) pts.push_back({s.x[i], s.y[i]});
        const std::vector<int> front = paretoFront(pts);
        for (size_t k = 1; k < front.size(); ++k) {
            const int x0 = X(s.x[front[k - 1]]), y0 = Y(s.y[front[k - 1]]), x1 = X(s.x[front[k]]), y1 = Y(s.y[front[k]]);
            draw::line(img, x0, y0, x1, y1, s.color);
            draw::line(img, x0, y0 + 1, x1, y1 + 1, s.color);
        }
        for (size_t i = 0; i < s.x.size(); ++i)
            if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) marker(img, X(s.x[i]), Y(s.y[i]), 3, s.color, true);
        for (int i : front) {
            marker(img, X(s.x[i]), Y(s.y[i]), 6, black, false);
            if (size_t(i) < s.labels.size()) draw::text(img, X(s.x[i]) + 8, Y(s.y[i]) - 16, s.labels[i], s.color);
        }
    }
    return img;
}

}  // namespace deepgi::bench
