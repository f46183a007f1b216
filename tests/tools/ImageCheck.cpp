// bounce_image_check: assertions on image files for the CMake-scripted tests (the viewer's
// screenshots and captures). Exit 0 when the assertion holds, 1 with one line saying why not.
//   halves FILE MIN MAX        mean |left half - right half| over pixels and channels is in [MIN, MAX]
//                              (a side-by-side screenshot: the two halves show A and B)
//   nonblank FILE MIN [X Y W H]  standard deviation of luminance over the image (or the W x H region
//                              at X, Y, pixels from the top left) is at least MIN
//   differ A B MIN MAX         relMSE of A against B (metrics/ErrorMetrics.h) is in [MIN, MAX]
//   size FILE W H              the image is W x H pixels
#include "core/ImageIo.h"
#include "metrics/ErrorMetrics.h"

#include <glm/common.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

using namespace bounce;

namespace {

Image load(const char* path) {
    auto image = readImage(path);
    if (!image.ok()) {
        std::fprintf(stderr, "bounce_image_check: %s\n", image.error().message.c_str());
        std::exit(1);
    }
    return std::move(*image);
}

int inRange(const char* what, double value, double lo, double hi) {
    const bool ok = value >= lo && value <= hi;
    std::printf("%s %s: %.6g (expected %.6g .. %.6g)\n", ok ? "ok" : "FAILED", what, value, lo, hi);
    return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "halves" && argc == 5) {
        const Image img = load(argv[2]);
        const int half = img.width() / 2;
        double sum = 0.0;
        for (int y = 0; y < img.height(); ++y)
            for (int x = 0; x < half; ++x) {
                const glm::vec3 d = glm::abs(img.at(x, y) - img.at(x + half, y));
                sum += d.r + d.g + d.b;
            }
        return inRange((std::string("halves of ") + argv[2]).c_str(), sum / (3.0 * half * img.height()), std::atof(argv[3]), std::atof(argv[4]));
    }
    if (mode == "nonblank" && (argc == 4 || argc == 8)) {
        const Image img = load(argv[2]);
        int x0 = 0, y0 = 0, w = img.width(), h = img.height();
        if (argc == 8) {
            x0 = std::atoi(argv[4]), y0 = std::atoi(argv[5]), w = std::atoi(argv[6]), h = std::atoi(argv[7]);
            if (x0 < 0 || y0 < 0 || w <= 0 || h <= 0 || x0 + w > img.width() || y0 + h > img.height()) {
                std::fprintf(stderr, "bounce_image_check: region %d,%d %dx%d is not inside %s (%dx%d)\n", x0, y0, w, h, argv[2],
                             img.width(), img.height());
                return 1;
            }
        }
        double s = 0.0, s2 = 0.0;
        for (int y = y0; y < y0 + h; ++y)
            for (int x = x0; x < x0 + w; ++x) {
                const double l = luminance(img.at(x, y));
                s += l;
                s2 += l * l;
            }
        const double n = static_cast<double>(w) * h;
        const double sd = std::sqrt(std::max(0.0, s2 / n - (s / n) * (s / n)));
        return inRange((std::string("luminance deviation of ") + argv[2]).c_str(), sd, std::atof(argv[3]), 1e30);
    }
    if (mode == "differ" && argc == 6) {
        const Image a = load(argv[2]), b = load(argv[3]);
        if (a.width() != b.width() || a.height() != b.height()) {
            std::fprintf(stderr, "bounce_image_check: %s is %dx%d, %s is %dx%d\n", argv[2], a.width(), a.height(), argv[3], b.width(), b.height());
            return 1;
        }
        return inRange((std::string("relMSE of ") + argv[2] + " vs " + argv[3]).c_str(), relativeSquaredErrorMap(a, b).mean(),
                       std::atof(argv[4]), std::atof(argv[5]));
    }
    if (mode == "size" && argc == 5) {
        const Image img = load(argv[2]);
        const bool ok = img.width() == std::atoi(argv[3]) && img.height() == std::atoi(argv[4]);
        std::printf("%s size of %s: %dx%d (expected %sx%s)\n", ok ? "ok" : "FAILED", argv[2], img.width(), img.height(), argv[3], argv[4]);
        return ok ? 0 : 1;
    }
    std::fprintf(stderr, "usage: bounce_image_check halves FILE MIN MAX | nonblank FILE MIN [X Y W H] | differ A B MIN MAX | size FILE W H\n");
    return 1;
}
