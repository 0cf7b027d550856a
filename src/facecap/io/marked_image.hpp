#pragma once
// Still-image output of an edit (a swap or a transformation of a photo),
// carrying the synthetic-media marks in the file itself, as a video carries
// them in its container tags (synthetic_mark.hpp):
//   - XMP (PNG iTXt "XML:com.adobe.xmp", JPEG APP1) with IPTC's
//     DigitalSourceType "compositeSynthetic" (the vocabulary of C2PA and of
//     photo agencies for "a composite with synthetic elements"), dc:description,
//     and facecap:synthetic / facecap:edit;
//   - the same tags as plain text: PNG iTXt chunks (`synthetic`,
//     `facecap_edit`, `Comment`, `Software`), a JPEG comment (COM) segment.
// Written atomically.
#include <filesystem>
#include <map>
#include <string>

#include <opencv2/core.hpp>

namespace facecap {

// Whether a path names a still image facecap writes: .png, .jpg or .jpeg
// (case-insensitive).
bool is_still_image_path(const std::filesystem::path& path);

// Writes `bgr` as PNG or JPEG (quality 95) by the path's extension, with
// `tags` (synthetic_metadata()) embedded as above. Throws facecap::Error for
// another extension or a failed write; nothing is left at the path then.
void write_marked_image(const std::filesystem::path& path, const cv::Mat& bgr,
                        const std::map<std::string, std::string>& tags);

// The facecap tags of a PNG or JPEG: its PNG text chunks, or the
// facecap:synthetic and facecap:edit properties of its XMP (as `synthetic`
// and `facecap_edit`), plus `xmp_digital_source_type` where the XMP has one.
// Empty for a file without them or not an image.
std::map<std::string, std::string> read_image_tags(const std::filesystem::path& path);

}  // namespace facecap
