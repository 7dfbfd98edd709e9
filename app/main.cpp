// ranryu: run | record | profile | scenes | validate | sweep | export-field. Errors end here: one line on stderr, and the exit code
// of their kind (0 ok, 1 failure, 2 bad input, 3 unstable simulation, 130 stopped by SIGINT or SIGTERM).
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "cli.h"
#include "commands.h"
#include "version.h"
#include "core/error.h"
#include "frame/stop.h"

int main(int argc, char** argv) {
    using namespace ranryu;
    try {
        const app::Options o = app::parse(std::vector<std::string>(argv + 1, argv + argc));
        if (o.command == "help") return std::fputs(app::usage().c_str(), stdout), 0;
        if (o.command == "version") return std::printf("ranryu %s (commit %s)\n", RANRYU_VERSION, app::commit()), 0;
        if (o.help) return std::fputs(app::command_help(o.command).c_str(), stdout), 0;
        // The headless runs stop at a frame boundary on SIGINT or SIGTERM, and exit 130.
        if (o.command == "record" || o.command == "profile" || o.command == "validate" || o.command == "sweep") frame::stop_on_signals();
        if (o.command == "run") return app::run(o);
        if (o.command == "record") return app::record(o);
        if (o.command == "profile") return app::profile_cmd(o);
        if (o.command == "scenes") return app::scenes(o);
        if (o.command == "validate") return app::validate(o);
        if (o.command == "sweep") return app::sweep(o);
        if (o.command == "export-field") return app::export_field(o);
        return 1;
    } catch (const Error& e) {
        std::fflush(stdout);
        std::fprintf(stderr, "ranryu: %s\n", e.what());
        return int(e.code());
    } catch (const std::exception& e) {
        std::fflush(stdout);
        std::fprintf(stderr, "ranryu: %s\n", e.what());
        return int(Exit::failure);
    }
}
