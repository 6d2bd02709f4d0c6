// `imagenets print-marker --marker M.yaml -o OUT.(png|pdf) [--dpi 300]`: the marker with its
// white margin at true scale, for printing. PNG: the resolution is stored (pHYs chunk), so
// "print at 100 %" gives the true size; PDF: the page is exactly the marker's size.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include <boost/crc.hpp>
#include <boost/filesystem.hpp>
#include <opencv2/imgcodecs.hpp>

#include "imagenets/tool/command.h"
#include "imagenets/vision/marker.h"

namespace imagenets {
namespace tool {
namespace {

void putU32(std::string& s, uint32_t v) {
  for (int i = 3; i >= 0; --i) s += static_cast<char>((v >> (8 * i)) & 0xff);
}

// Inserts a pHYs chunk (pixels per metre) after the IHDR chunk of a PNG.
std::string withResolution(const std::vector<uchar>& png, double pixels_per_metre) {
  std::string chunk_data;
  const uint32_t ppm = static_cast<uint32_t>(std::lround(pixels_per_metre));
  putU32(chunk_data, ppm);
  putU32(chunk_data, ppm);
  chunk_data += '\x01';  // unit: metre
  const std::string type_and_data = "pHYs" + chunk_data;
  boost::crc_32_type crc;
  crc.process_bytes(type_and_data.data(), type_and_data.size());
  std::string chunk;
  putU32(chunk, static_cast<uint32_t>(chunk_data.size()));
  chunk += type_and_data;
  putU32(chunk, crc.checksum());
  const size_t after_ihdr = 8 + 4 + 4 + 13 + 4;  // signature, length, "IHDR", data, CRC
  std::string out(png.begin(), png.end());
  out.insert(after_ihdr, chunk);
  return out;
}

// A one-page PDF whose page is the image at `size_m` x `size_m` (uncompressed 8-bit gray image).
std::string pdfOf(const cv::Mat& gray, double size_m) {
  const double pt = size_m / 0.0254 * 72.0;
  std::ostringstream content;
  content.setf(std::ios::fixed);
  content.precision(4);
  content << "q " << pt << " 0 0 " << pt << " 0 0 cm /Im0 Do Q\n";
  const std::string c = content.str();
  std::vector<std::string> objects;
  objects.push_back("<< /Type /Catalog /Pages 2 0 R >>");
  objects.push_back("<< /Type /Pages /Kids [3 0 R] /Count 1 >>");
  {
    std::ostringstream page;
    page.setf(std::ios::fixed);
    page.precision(4);
    page << "<< /Type /Page /Parent 2 0 R /MediaBox [0 0 " << pt << " " << pt
         << "] /Resources << /XObject << /Im0 5 0 R >> >> /Contents 4 0 R >>";
    objects.push_back(page.str());
  }
  objects.push_back("<< /Length " + std::to_string(c.size()) + " >>\nstream\n" + c + "endstream");
  std::string pixels(reinterpret_cast<const char*>(gray.data), gray.total());
  objects.push_back("<< /Type /XObject /Subtype /Image /Width " + std::to_string(gray.cols) + " /Height " +
                    std::to_string(gray.rows) + " /ColorSpace /DeviceGray /BitsPerComponent 8 /Length " +
                    std::to_string(pixels.size()) + " >>\nstream\n" + pixels + "\nendstream");
  std::string pdf = "%PDF-1.4\n";
  std::vector<size_t> offsets;
  for (size_t i = 0; i < objects.size(); ++i) {
    offsets.push_back(pdf.size());
    pdf += std::to_string(i + 1) + " 0 obj\n" + objects[i] + "\nendobj\n";
  }
  const size_t xref = pdf.size();
  pdf += "xref\n0 " + std::to_string(objects.size() + 1) + "\n0000000000 65535 f \n";
  for (size_t off : offsets) {
    char line[32];
    std::snprintf(line, sizeof(line), "%010zu 00000 n \n", off);
    pdf += line;
  }
  pdf += "trailer\n<< /Size " + std::to_string(objects.size() + 1) + " /Root 1 0 R >>\nstartxref\n" +
         std::to_string(xref) + "\n%%EOF\n";
  return pdf;
}

void declare(Flags& f) {
  f.add()("marker", po::value<std::string>(), "the marker description (MARKER.yaml)")
      ("output,o", po::value<std::string>(), "OUT.png (with its resolution) or OUT.pdf")
      ("dpi", po::value<double>()->default_value(300), "dots per inch, 50..2400");
}

int run(const Options& o) {
  const std::string marker_path = stringFlag(o, "marker"), out_path = stringFlag(o, "output");
  const double dpi = o["dpi"].as<double>();
  if (marker_path.empty() || out_path.empty()) throw UsageError("needs --marker MARKER.yaml and -o OUT.png|OUT.pdf");
  if (!(dpi >= 50 && dpi <= 2400)) throw UsageError("--dpi must be 50..2400");
  const std::string ext = boost::filesystem::path(out_path).extension().string();
  if (ext != ".png" && ext != ".pdf") throw UsageError("output '" + out_path + "' must end in .png or .pdf");
  marker::MarkerDescription m;
  try {
    m = marker::MarkerDescription::load(marker_path);
  } catch (const std::exception& e) {
    std::cerr << "imagenets print-marker: " << e.what() << "\n";
    return 1;
  }
  const cv::Mat tex = m.texture(dpi / 0.0254, true);
  // Whole pixels round the border and inner widths: scale the output so the black border is
  // exactly `size` wide (the resolution then differs from --dpi by a fraction of a percent).
  const double marker_px = 2.0 * std::lround(m.border * m.size * dpi / 0.0254) + std::lround(m.innerSize() * dpi / 0.0254);
  const double ppm = marker_px / m.size;
  const double printed = tex.cols / ppm;  // metres
  std::string bytes;
  if (ext == ".png") {
    std::vector<uchar> png;
    cv::imencode(".png", tex, png);
    bytes = withResolution(png, ppm);
  } else {
    bytes = pdfOf(tex, printed);
  }
  const std::string tmp = out_path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) {
      std::cerr << "imagenets print-marker: cannot write '" << tmp << "'\n";
      return 1;
    }
  }
  boost::filesystem::rename(tmp, out_path);
  std::cout << "wrote " << out_path << ": marker '" << m.name << "', black border " << m.size * 1000 << " mm, sheet "
            << printed * 1000 << " mm square at " << ppm * 0.0254 << " dpi. Print at 100 % (no fit-to-page) and check the"
            << " border measures " << m.size * 1000 << " mm.\n";
  return 0;
}

}  // namespace

IMAGENETS_TOOL_COMMAND(print_marker, "print-marker", "print-marker --marker MARKER.yaml -o OUT.png|OUT.pdf [--dpi 300]",
                       "write a square marker at true scale for printing (PNG with resolution, or PDF)", declare,
                       run);

}  // namespace tool
}  // namespace imagenets
