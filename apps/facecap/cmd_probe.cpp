#include <cmath>

#include "commands.hpp"
#include "facecap/pipeline/probe.hpp"

namespace facecap::cli {

void register_probe(CLI::App& app, GlobalOptions&) {
  auto* cmd = app.add_subcommand(
      "probe",
      "Describe an input (video, image, image folder or cam:N) as JSON, with the faces of "
      "its first frame (face_boxes, left to right: a centre is a --face X,Y; roll_degrees: a face's roll "
      "to within about 30 degrees, the turn of the view it was found in: steps of 45 degrees, or 22.5 off them "
      "where only the views between show the face)");
  auto input = std::make_shared<std::string>();
  cmd->add_option("INPUT", *input, "Video file, image, folder of images, or cam:N")->required();
  cmd->callback([input] {
    const ProbeReport r = probe_input(*input);
    // Where each face is, for track's --face X,Y: its box and centre, rounded to the pixel.
    nlohmann::json boxes = nlohmann::json::array();
    for (const ProbeFace& f : r.found) {
      const Box& b = f.box;
      boxes.push_back({{"x", std::lround(b.x)},
                       {"y", std::lround(b.y)},
                       {"width", std::lround(b.width)},
                       {"height", std::lround(b.height)},
                       {"centre", {std::lround(b.center().x()), std::lround(b.center().y())}},
                       {"roll_degrees", double(f.roll_degrees)}});
    }
    nlohmann::json report = {{"input", r.info.spec},
                             {"kind", to_string(r.info.kind)},
                             {"width", r.info.width},
                             {"height", r.info.height},
                             {"fps", r.info.fps},
                             {"frames", r.info.frames},
                             {"duration", r.info.duration},
                             {"audio", r.info.audio},
                             {"faces", r.faces},
                             {"face_boxes", boxes}};
    // A file cut short: the frames its index lists past the end, which no reading will give.
    if (r.info.frames_past_end > 0) report["frames_past_end"] = r.info.frames_past_end;
    print_json(report);
  });
}

}  // namespace facecap::cli
