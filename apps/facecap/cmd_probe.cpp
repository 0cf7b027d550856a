#include "commands.hpp"
#include "facecap/pipeline/probe.hpp"

namespace facecap::cli {

void register_probe(CLI::App& app, GlobalOptions&) {
  auto* cmd = app.add_subcommand("probe", "Describe an input (video, image, image folder or cam:N) as JSON");
  auto input = std::make_shared<std::string>();
  cmd->add_option("INPUT", *input, "Video file, image, folder of images, or cam:N")->required();
  cmd->callback([input] {
    const ProbeReport r = probe_input(*input);
    print_json({{"input", r.info.spec},
                {"kind", to_string(r.info.kind)},
                {"width", r.info.width},
                {"height", r.info.height},
                {"fps", r.info.fps},
                {"frames", r.info.frames},
                {"duration", r.info.duration},
                {"audio", r.info.audio},
                {"faces", r.faces}});
  });
}

}  // namespace facecap::cli
