#include "facecap/io/marked_image.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <optional>
#include <vector>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"
#include "facecap/io/image_file.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

using Bytes = std::vector<uint8_t>;

constexpr const char* kXmpNamespace = "urn:facecap:ns:1.0/";
constexpr const char* kDigitalSourceType = "http://cv.iptc.org/newscodes/digitalsourcetype/compositeSynthetic";
constexpr const char* kXmpJpegHeader = "http://ns.adobe.com/xap/1.0/";  // followed by a NUL
constexpr std::array<uint8_t, 8> kPngSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

std::string extension_of(const fs::path& path) {
  std::string e = path.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

bool is_jpeg_path(const fs::path& path) {
  const std::string e = extension_of(path);
  return e == ".jpg" || e == ".jpeg";
}

std::string xml_escaped(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string tag(const std::map<std::string, std::string>& tags, const std::string& key) {
  const auto it = tags.find(key);
  return it == tags.end() ? std::string() : it->second;
}

std::string xmp_packet(const std::map<std::string, std::string>& tags) {
  return std::string("<?xpacket begin=\"\xEF\xBB\xBF\" id=\"W5M0MpCehiHzreSzNTczkc9d\"?>\n") +
         "<x:xmpmeta xmlns:x=\"adobe:ns:meta/\">\n"
         " <rdf:RDF xmlns:rdf=\"http://www.w3.org/1999/02/22-rdf-syntax-ns#\">\n"
         "  <rdf:Description rdf:about=\"\"\n"
         "    xmlns:dc=\"http://purl.org/dc/elements/1.1/\"\n"
         "    xmlns:xmp=\"http://ns.adobe.com/xap/1.0/\"\n"
         "    xmlns:Iptc4xmpExt=\"http://iptc.org/std/Iptc4xmpExt/2008-02-29/\"\n"
         "    xmlns:facecap=\"" +
         kXmpNamespace +
         "\"\n"
         "    Iptc4xmpExt:DigitalSourceType=\"" +
         kDigitalSourceType + "\"\n    xmp:CreatorTool=\"" + xml_escaped(tag(tags, "encoder_note")) +
         "\"\n    facecap:synthetic=\"" + xml_escaped(tag(tags, "synthetic")) + "\"\n    facecap:edit=\"" +
         xml_escaped(tag(tags, "facecap_edit")) +
         "\">\n"
         "   <dc:description><rdf:Alt><rdf:li xml:lang=\"x-default\">" +
         xml_escaped(tag(tags, "comment")) +
         "</rdf:li></rdf:Alt></dc:description>\n"
         "  </rdf:Description>\n"
         " </rdf:RDF>\n"
         "</x:xmpmeta>\n"
         "<?xpacket end=\"w\"?>";
}

// --------------------------------------------------------------------- PNG

uint32_t crc32(const uint8_t* data, size_t n, uint32_t crc = 0xffffffffu) {
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t i = 0; i < 256; ++i) {
      uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  for (size_t i = 0; i < n; ++i) crc = table[(crc ^ data[i]) & 0xff] ^ (crc >> 8);
  return crc;
}

void put_u32(Bytes& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(uint8_t(v >> shift));
}

uint32_t get_u32(const Bytes& in, size_t at) {
  return uint32_t(in[at]) << 24 | uint32_t(in[at + 1]) << 16 | uint32_t(in[at + 2]) << 8 | in[at + 3];
}

// An uncompressed iTXt chunk (PNG 1.2, 11.3.4.5): UTF-8 text under a keyword.
Bytes itxt_chunk(const std::string& keyword, const std::string& text) {
  Bytes body(keyword.begin(), keyword.end());
  body.insert(body.end(), {0, 0, 0, 0, 0});  // NUL, uncompressed, method 0, no language, no translation
  body.insert(body.end(), text.begin(), text.end());
  Bytes chunk;
  put_u32(chunk, uint32_t(body.size()));
  const char type[] = "iTXt";
  chunk.insert(chunk.end(), type, type + 4);
  chunk.insert(chunk.end(), body.begin(), body.end());
  put_u32(chunk, crc32(chunk.data() + 4, chunk.size() - 4) ^ 0xffffffffu);
  return chunk;
}

Bytes marked_png(const Bytes& png, const std::map<std::string, std::string>& tags) {
  // The chunks go right after IHDR, the first chunk (8 + 4 + 4 + 13 + 4 bytes in).
  constexpr size_t kAfterHeader = 8 + 25;
  if (png.size() < kAfterHeader || !std::equal(kPngSignature.begin(), kPngSignature.end(), png.begin()))
    throw Error("the PNG encoder gave no PNG");
  Bytes out(png.begin(), png.begin() + kAfterHeader);
  auto add = [&](const Bytes& chunk) { out.insert(out.end(), chunk.begin(), chunk.end()); };
  add(itxt_chunk("synthetic", tag(tags, "synthetic")));
  add(itxt_chunk("facecap_edit", tag(tags, "facecap_edit")));
  add(itxt_chunk("Comment", tag(tags, "comment")));
  add(itxt_chunk("Software", tag(tags, "encoder_note")));
  add(itxt_chunk("XML:com.adobe.xmp", xmp_packet(tags)));
  out.insert(out.end(), png.begin() + kAfterHeader, png.end());
  return out;
}

// -------------------------------------------------------------------- JPEG

Bytes jpeg_segment(uint8_t marker, const std::string& payload) {
  if (payload.size() + 2 > 0xffff) throw Error("image metadata too long for a JPEG segment");
  Bytes s = {0xff, marker, uint8_t((payload.size() + 2) >> 8), uint8_t((payload.size() + 2) & 0xff)};
  s.insert(s.end(), payload.begin(), payload.end());
  return s;
}

Bytes marked_jpeg(const Bytes& jpeg, const std::map<std::string, std::string>& tags) {
  if (jpeg.size() < 4 || jpeg[0] != 0xff || jpeg[1] != 0xd8) throw Error("the JPEG encoder gave no JPEG");
  // After the JFIF APP0 segment where there is one (readers expect it first).
  size_t at = 2;
  if (jpeg[2] == 0xff && jpeg[3] == 0xe0) at = 4 + (size_t(jpeg[4]) << 8 | jpeg[5]);
  Bytes out(jpeg.begin(), jpeg.begin() + at);
  const Bytes xmp = jpeg_segment(0xe1, std::string(kXmpJpegHeader) + '\0' + xmp_packet(tags));
  const Bytes comment = jpeg_segment(0xfe, tag(tags, "comment"));
  out.insert(out.end(), xmp.begin(), xmp.end());
  out.insert(out.end(), comment.begin(), comment.end());
  out.insert(out.end(), jpeg.begin() + at, jpeg.end());
  return out;
}

// ------------------------------------------------------------ reading back

// The value of `name="..."` in an XMP packet, or "".
std::string xmp_attribute(const std::string& xmp, const std::string& name) {
  const std::string key = name + "=\"";
  const size_t at = xmp.find(key);
  if (at == std::string::npos) return "";
  const size_t end = xmp.find('"', at + key.size());
  return end == std::string::npos ? "" : xmp.substr(at + key.size(), end - at - key.size());
}

void add_xmp_tags(const std::string& xmp, std::map<std::string, std::string>& tags) {
  if (const std::string v = xmp_attribute(xmp, "facecap:synthetic"); !v.empty()) tags["synthetic"] = v;
  if (const std::string v = xmp_attribute(xmp, "facecap:edit"); !v.empty()) tags["facecap_edit"] = v;
  if (const std::string v = xmp_attribute(xmp, "Iptc4xmpExt:DigitalSourceType"); !v.empty())
    tags["xmp_digital_source_type"] = v;
}

std::map<std::string, std::string> png_tags(const Bytes& png) {
  std::map<std::string, std::string> tags;
  size_t at = 8;
  while (at + 12 <= png.size()) {
    const uint32_t length = get_u32(png, at);
    if (at + 12 + length > png.size()) break;
    const std::string type(png.begin() + at + 4, png.begin() + at + 8);
    const std::string body(png.begin() + at + 8, png.begin() + at + 8 + length);
    if (type == "iTXt" || type == "tEXt") {
      const size_t nul = body.find('\0');
      if (nul != std::string::npos) {
        const std::string keyword = body.substr(0, nul);
        std::string text = body.substr(nul + 1);
        if (type == "iTXt") {
          // compression flag and method, then language and translated keyword, each NUL-ended
          if (text.size() < 2 || text[0] != 0) {
            text.clear();
          } else {
            size_t p = 2;
            for (int skip = 0; skip < 2 && p != std::string::npos; ++skip) {
              p = text.find('\0', p);
              if (p != std::string::npos) ++p;
            }
            text = p == std::string::npos ? "" : text.substr(p);
          }
        }
        if (keyword == "XML:com.adobe.xmp") {
          add_xmp_tags(text, tags);
        } else {
          tags[keyword] = text;
        }
      }
    }
    if (type == "IEND") break;
    at += 12 + length;
  }
  return tags;
}

std::map<std::string, std::string> jpeg_tags(const Bytes& jpeg) {
  std::map<std::string, std::string> tags;
  size_t at = 2;
  const std::string header = std::string(kXmpJpegHeader) + '\0';
  while (at + 4 <= jpeg.size() && jpeg[at] == 0xff) {
    const uint8_t marker = jpeg[at + 1];
    if (marker == 0xda || marker == 0xd9) break;  // the image data: no metadata after it
    const size_t length = size_t(jpeg[at + 2]) << 8 | jpeg[at + 3];
    if (length < 2 || at + 2 + length > jpeg.size()) break;
    const std::string payload(jpeg.begin() + at + 4, jpeg.begin() + at + 2 + length);
    if (marker == 0xe1 && payload.starts_with(header)) add_xmp_tags(payload.substr(header.size()), tags);
    if (marker == 0xfe) tags["comment"] = payload;
    at += 2 + length;
  }
  return tags;
}

}  // namespace

bool is_still_image_path(const fs::path& path) {
  const std::string e = extension_of(path);
  return e == ".png" || e == ".jpg" || e == ".jpeg";
}

void write_marked_image(const fs::path& path, const cv::Mat& bgr, const std::map<std::string, std::string>& tags) {
  if (!is_still_image_path(path))
    throw Error("cannot write an image to " + path.string() + ": its name must end in .png, .jpg or .jpeg");
  if (bgr.empty()) throw Error("no image to write to " + path.string());
  const bool jpeg = is_jpeg_path(path);
  const Bytes encoded = jpeg ? encode_jpeg(bgr, 95) : encode_png(bgr);
  const Bytes marked = jpeg ? marked_jpeg(encoded, tags) : marked_png(encoded, tags);
  write_binary_file(path, marked.data(), marked.size());
}

std::map<std::string, std::string> read_image_tags(const fs::path& path) {
  const std::optional<Bytes> read = read_binary_file(path);
  if (!read) return {};
  const Bytes& bytes = *read;
  if (bytes.size() >= 8 && std::equal(kPngSignature.begin(), kPngSignature.end(), bytes.begin()))
    return png_tags(bytes);
  if (bytes.size() >= 4 && bytes[0] == 0xff && bytes[1] == 0xd8) return jpeg_tags(bytes);
  return {};
}

}  // namespace facecap
