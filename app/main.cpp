// bounce: the command-line entry point. Dispatches to the subcommands of app/commands.h.
#include <cstdio>
#include <exception>
#include <string>

#include "app/commands.h"
#include "gl/resource/resource_error.h"

namespace {

const char* kUsage = "bounce - a real-time global-illumination laboratory\n"
                     "\n"
                     "usage: bounce <command> [options]    (bounce <command> --help for its options)\n"
                     "\n"
                     "commands:\n"
                     "  render     render a scene with one technique to EXR/PNG, with per-pass GPU timings\n"
                     "  list       list the built-in scenes, the techniques and their parameters\n"
                     "  demo       open a window: fly camera, technique toggles, side-by-side comparison\n"
                     "  reference  render the ground truth with the CPU path tracer (cached)\n"
                     "  compare    error metrics between two images (RMSE, relative RMSE, SSIM...)\n"
                     "  bench      sweep scenes x techniques x parameters, report speed against error\n"
                     "  rays       GPU ray casting against Embree: rays per second, coherent and incoherent\n"
                     "  probe      this machine's ceilings (FLOP/s, fetches, bandwidth) for every pass's bound\n";

// The parameter that lowers a GL resource that could not be had, by the resource's label.
std::string lowerWith(const std::string& label)
{
    const auto starts = [&](const char* p) { return label.rfind(p, 0) == 0; };
    if (starts("shadow")) return "lower the frame parameter shadow.size (--set shadow.size=512), or use fewer lights";
    if (starts("rsm")) return "lower the technique's rsmSize (--set rsmSize=128)";
    if (starts("scene.baseColorTextures")) return "lower the frame parameter textures.size";
    return "lower --size or the technique's buffer sizes (`bounce list`)";
}

} // namespace

int main(int argc, char** argv)
{
    using namespace bounce::app;
    if (argc < 2) {
        std::fputs(kUsage, stderr);
        return 2;
    }
    const std::string cmd = argv[1];
    const Args args(argv + 2, argv + argc);
    try {
        if (cmd == "--help" || cmd == "-h" || cmd == "help") {
            std::fputs(kUsage, stdout);
            return 0;
        }
        if (cmd == "render") return cmdRender(args);
        if (cmd == "list") return cmdList(args);
        if (cmd == "demo") return cmdDemo(args);
        if (cmd == "reference") return cmdReference(args);
        if (cmd == "compare") return cmdCompare(args);
        if (cmd == "bench") return cmdBench(args);
        if (cmd == "rays") return cmdRays(args);
        if (cmd == "probe") return cmdProbe(args);
        std::fprintf(stderr, "bounce: unknown command '%s'\n\n%s", cmd.c_str(), kUsage);
        return 2;
    } catch (const UsageError& e) {
        std::fprintf(stderr, "bounce %s: %s\n", cmd.c_str(), e.what());
        return 2;
    } catch (const bounce::gl::ResourceError& e) {
        std::fprintf(stderr, "bounce %s: %s; %s\n", cmd.c_str(), e.what(), lowerWith(e.label).c_str());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bounce %s: error: %s\n", cmd.c_str(), e.what());
        return 1;
    }
}
