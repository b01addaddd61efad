#pragma once
// A tiny 8-bit RGB raster for the bench's plots and image grids: points, lines, rectangles and a built-in 5x7
// bitmap font (upper-case letters, digits and a little punctuation; lower case is drawn as upper case).
#include <cstdint>
#include <string>
#include <vector>

namespace deepgi::bench {

struct Rgb {
    uint8_t r, g, b;
};

class Canvas {
public:
    Canvas(int width, int height, Rgb background = {255, 255, 255});
    int width() const { return w_; }
    int height() const { return h_; }
    void set(int x, int y, Rgb c);
    Rgb get(int x, int y) const;
    void fillRect(int x0, int y0, int x1, int y1, Rgb c);  // inclusive-exclusive
    void line(int x0, int y0, int x1, int y1, Rgb c, int thickness = 1);
    void disc(int cx, int cy, int radius, Rgb c);
    void ring(int cx, int cy, int radius, Rgb c);
    // Text with its top-left corner at (x, y); each font pixel drawn as scale x scale. Returns the width drawn.
    int text(int x, int y, const std::string& s, Rgb c, int scale = 1);
    static int textWidth(const std::string& s, int scale = 1) { return int(s.size()) * 6 * scale; }
    // Copies an 8-bit RGB (channels 3) or RGBA (4) image with row 0 at the top.
    void blit(int x, int y, int w, int h, int channels, const std::vector<unsigned char>& px);
    const std::vector<unsigned char>& pixels() const { return px_; }
    void savePng(const std::string& path) const;

private:
    int w_, h_;
    std::vector<unsigned char> px_;
};

// One series of points in a speed-against-error plot.
struct PlotSeries {
    std::string name;
    Rgb color;
    std::vector<double> x, y;
    std::vector<std::string> labels;  // drawn next to the points of the Pareto front
};

// Scatter plot, x and y both minimised; each series' Pareto front is joined by a line and its points circled and
// labelled. Axes from 0 (x) and 0 (y) to a rounded maximum, with ticks and labels.
Canvas speedErrorPlot(const std::vector<PlotSeries>& series, const std::string& title, const std::string& xLabel,
                      const std::string& yLabel, int width = 900, int height = 600);

// Heat-map colour of t in [0, 1] (black, purple, orange, yellow).
Rgb heat(double t);

}  // namespace deepgi::bench
