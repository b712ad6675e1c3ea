// docs/MATERIALS.md "Why not OpenImageIO's TextureSystem": Prism's MIPMap (EWA, trilinear) against
// OIIO's TextureSystem on one image and the same 2 million lookups (random positions,
// anisotropic footprints from 1/8 to 64 texels), one thread. Built with the project
// (bench/CMakeLists.txt):
//   build/bench/texture_lookup_bench ../shared/scenes/pbrt-spheres-differentials-texfilt/textures/lines.png
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/texture.h>
#include <chrono>
#include <cstdio>
#include <random>
#include "image/image.h"
#include "render/mipmap.h"
using namespace prism;
int main(int argc, char **argv) {
    const char *file = argv[1];
    const int N = 2000000;
    // lookups: random st, anisotropic footprints from 0.1 to 50 texels (minified surfaces)
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(0, 1);
    struct L { float s, t, dsdx, dtdx, dsdy, dtdy; };
    std::vector<L> ls(N);
    OIIO::ImageBuf buf(file);
    buf.read(0, 0, true, OIIO::TypeDesc::FLOAT);
    int w = buf.spec().width, h = buf.spec().height, nc = buf.spec().nchannels;
    for (auto &l : ls) {
        float major = std::pow(2.f, u(rng) * 9 - 3) / w, aniso = 1 + 7 * u(rng), a = 6.283f * u(rng);
        l = {u(rng), u(rng), major * std::cos(a), major * std::sin(a),
             -major / aniso * std::sin(a), major / aniso * std::cos(a)};
    }
    auto img = std::make_shared<Image>(w, h, 3);
    for (int y = 0; y < h; ++y) for (int x = 0; x < w; ++x) {
        float px[4] = {0,0,0,0}; buf.getpixel(x, y, px, 4);
        img->SetRGB(x, y, nc >= 3 ? RGB(px[0], px[1], px[2]) : RGB(px[0]));
    }
    auto t0 = std::chrono::steady_clock::now();
    MIPMap mip(img, WrapMode::Repeat);
    auto t1 = std::chrono::steady_clock::now();
    double sum = 0;
    for (auto &l : ls) sum += mip.EWA({l.s, l.t}, {l.dsdx * .5f, l.dtdx * .5f}, {l.dsdy * .5f, l.dtdy * .5f}, 8).r;
    auto t2 = std::chrono::steady_clock::now();
    for (auto &l : ls) {
        float wd = std::max(std::max(std::abs(l.dsdx), std::abs(l.dtdx)), std::max(std::abs(l.dsdy), std::abs(l.dtdy)));
        sum += mip.Trilinear({l.s, l.t}, wd).r;
    }
    auto t3 = std::chrono::steady_clock::now();
    OIIO::TextureSystem *ts = OIIO::TextureSystem::create(true);
    ts->attribute("automip", 1);
    OIIO::TextureOpt opt;
    opt.swrap = opt.twrap = OIIO::TextureOpt::WrapPeriodic;
    opt.anisotropic = 8;
    opt.mipmode = OIIO::TextureOpt::MipModeAniso;
    OIIO::ustring name(file);
    auto handle = ts->get_texture_handle(name);
    float res[3];
    auto t4 = std::chrono::steady_clock::now();
    ts->texture(handle, nullptr, opt, 0.5f, 0.5f, 0, 0, 0, 0, 3, res);  // first use: builds MIP
    auto t5 = std::chrono::steady_clock::now();
    auto *pt = ts->get_perthread_info();
    for (auto &l : ls) {
        ts->texture(handle, pt, opt, l.s, 1 - l.t, l.dsdx, -l.dtdx, l.dsdy, -l.dtdy, 3, res);
        sum += res[0];
    }
    auto t6 = std::chrono::steady_clock::now();
    opt.mipmode = OIIO::TextureOpt::MipModeTrilinear;
    for (auto &l : ls) {
        ts->texture(handle, pt, opt, l.s, 1 - l.t, l.dsdx, -l.dtdx, l.dsdy, -l.dtdy, 3, res);
        sum += res[0];
    }
    auto t7 = std::chrono::steady_clock::now();
    auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
    std::printf("image %dx%d, %d lookups\n", w, h, N);
    std::printf("Prism MIPMap build %.1f ms; EWA %.1f ns/lookup; trilinear %.1f ns/lookup\n", ms(t0, t1), ms(t1, t2) * 1e6 / N, ms(t2, t3) * 1e6 / N);
    std::printf("OIIO TextureSystem first lookup (MIP build) %.1f ms; aniso %.1f ns/lookup; trilinear %.1f ns/lookup\n", ms(t4, t5), ms(t5, t6) * 1e6 / N, ms(t6, t7) * 1e6 / N);
    std::printf("(checksum %g)\n", sum);
    OIIO::TextureSystem::destroy(ts);
}
