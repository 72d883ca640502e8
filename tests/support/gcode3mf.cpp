#include "support/gcode3mf.hpp"

#include <minizip/unzip.h>
#include <minizip/zip.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "gcode/archive.hpp"
#include "support/files.hpp"

namespace scaffold::testing {

namespace {

std::string f(const char* format, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}

// Bambu Studio's G-code body: relative E, feature comments, travels with
// retraction, layers announced by '; CHANGE_LAYER'.
struct BambuWriter {
    double h = 0.2, w = 0.42, x = 0, y = 0, total_e = 0;
    std::string s;
    double e_per_mm() const { return w * h / (std::numbers::pi * 0.875 * 0.875); }
    void travel(double tx, double ty) {
        s += "G1 E-.8 F1800\nG1 X" + f("%.3f", tx) + " Y" + f("%.3f", ty) + " F12000\nG1 E.8 F1800\n";
        x = tx, y = ty;
    }
    void line(double tx, double ty) {
        double e = std::hypot(tx - x, ty - y) * e_per_mm();
        total_e += e;
        s += "G1 X" + f("%.3f", tx) + " Y" + f("%.3f", ty) + " E" + f("%.5f", e) + "\n";
        x = tx, y = ty;
    }
    void rect(double x0, double y0, double x1, double y1) {
        s += "; FEATURE: Outer wall\n; LINE_WIDTH: 0.42\nG1 F6000\n";
        travel(x0, y0);
        line(x1, y0), line(x1, y1), line(x0, y1), line(x0, y0);
        s += "; FEATURE: Internal solid infill\n";
        travel(x0 + w, y0 + w);
        bool right = true;
        for (double yy = y0 + w; yy <= y1 - w + 1e-9; yy += w) {
            if (yy > y0 + w) line(x, yy);
            line(right ? x1 - w : x0 + w, yy);
            right = !right;
        }
    }
};

}  // namespace

std::string bambu_gcode(const BambuPlate& p) {
    BambuWriter b;
    const int layers = 40;  // 8 mm
    for (int l = 1; l <= layers; ++l) {
        const double z = 0.2 * l;
        b.s += "; CHANGE_LAYER\n; Z_HEIGHT: " + f("%.1f", z) + "\n; LAYER_HEIGHT: 0.2\n";
        b.s += "M73 L" + std::to_string(l) + "\nG1 Z" + f("%.1f", z) + " F1200\n";
        b.rect(p.x, p.y, p.x + 10, p.y + 10);
        if (p.overhang && l >= 20 && l <= 22) b.rect(p.x + 10, p.y, p.x + 20, p.y + 10);  // the shelf, in mid-air
    }
    const double mm = b.total_e, cm3 = mm * std::numbers::pi * 0.875 * 0.875 / 1000, g = cm3 * 1.26;
    std::string out = "; HEADER_BLOCK_START\n; BambuStudio 01.09.00.70\n";
    out +=
        "; model printing time: 7m 30s; total estimated time: 9m 12s\n; total layer number: " + std::to_string(layers) +
        "\n";
    out += "; total filament length [mm] : " + f("%.2f", mm) +
           "\n; total filament volume [cm^3] : " + f("%.2f", cm3 * 1000) + "\n";
    out += "; total filament weight [g] : " + f("%.2f", g) + "\n; filament_density: 1.26\n; filament_diameter: 1.75\n";
    out += "; max_z_height: 8.00\n; HEADER_BLOCK_END\n\n; EXECUTABLE_BLOCK_START\n";
    out += "M73 P0 R9\nM201 X20000 Y20000 Z500 E5000\nM1002 gcode_claim_action : 2\nM140 S55\nM104 S220\nG28\n";
    out += "M190 S55\nM109 S220\nG90\nM83\n";
    out += b.s;
    out += "M73 P100 R0\nM104 S0\nM140 S0\nG1 Z12 F600\n; EXECUTABLE_BLOCK_END\n";
    out += "; filament used [mm] = " + f("%.2f", mm) + "\n; filament used [cm3] = " + f("%.2f", cm3) + "\n";
    out += "; filament used [g] = " + f("%.2f", g) + "\n; filament cost = " + f("%.2f", g / 1000 * 24.99) + "\n";
    out += "; total filament used [g] = " + f("%.2f", g) + "\n; total filament cost = " + f("%.2f", g / 1000 * 24.99) +
           "\n";
    out += "; total layers count = " + std::to_string(layers) + "\n\n; CONFIG_BLOCK_START\n";
    out += "; layer_height = 0.2\n; initial_layer_print_height = 0.2\n; nozzle_diameter = 0.4\n";
    out += "; filament_diameter = 1.75\n; filament_density = 1.26\n; filament_cost = 24.99\n";
    out += "; filament_type = PLA\n; printable_area = 0x0,256x0,256x256,0x256\n; retraction_length = 0.8\n";
    out += "; travel_speed = 500\n; enable_support = 0\n; print_sequence = by layer\n";
    out += std::string("; spiral_mode = ") + (p.spiral ? "1" : "0") + "\n; CONFIG_BLOCK_END\n";
    return out;
}

std::string bambu_slice_info(const std::vector<std::string>& plates) {
    std::string x =
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<config>\n  <header>\n"
        "    <header_item key=\"X-BBL-Client-Type\" value=\"slicer\"/>\n"
        "    <header_item key=\"X-BBL-Client-Version\" value=\"01.09.00.70\"/>\n  </header>\n";
    for (std::size_t i = 0; i < plates.size(); ++i) {
        x += "  <plate>\n    <metadata key=\"index\" value=\"" + std::to_string(i + 1) + "\"/>\n";
        x += "    <metadata key=\"printer_model_id\" value=\"C12\"/>\n    <metadata key=\"nozzle_diameters\" "
             "value=\"0.4\"/>\n";
        x += "    <metadata key=\"prediction\" value=\"552\"/>\n    <metadata key=\"weight\" value=\"3.10\"/>\n";
        x += "    <metadata key=\"outside\" value=\"false\"/>\n    <metadata key=\"support_used\" value=\"false\"/>\n";
        x += "    <object identify_id=\"" + std::to_string(100 + i) + "\" name=\"block.stl\" skipped=\"false\" />\n";
        x += "    <filament id=\"1\" tray_info_idx=\"GFA00\" type=\"PLA\" color=\"#FFFFFF\" used_m=\"1.03\" "
             "used_g=\"3.10\" />\n";
        x += "  </plate>\n";
    }
    return x + "</config>\n";
}

std::vector<ZipMember> bambu_members(const std::vector<std::string>& plates) {
    std::vector<ZipMember> m;
    std::string png = "\x89PNG\r\n\x1a\n";
    png += std::string(600, '\x11');
    m.push_back(
        {"[Content_Types].xml",
         "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Types xmlns=\"http://schemas.openxmlformats.org/package/2006/"
         "content-types\">\n <Default Extension=\"rels\" ContentType=\"application/"
         "vnd.openxmlformats-package.relationships+xml\"/>\n <Default Extension=\"model\" "
         "ContentType=\"application/vnd.ms-package.3dmanufacturing-3dmodel+xml\"/>\n <Default Extension=\"png\" "
         "ContentType=\"image/png\"/>\n <Default Extension=\"gcode\" ContentType=\"text/x.gcode\"/>\n</Types>\n"});
    m.push_back({"_rels/.rels", "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Relationships/>\n"});
    m.push_back({"3D/3dmodel.model", "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<model unit=\"millimeter\"/>\n"});
    for (std::size_t i = 0; i < plates.size(); ++i) {
        std::string n = std::to_string(i + 1);
        m.push_back({"Metadata/plate_" + n + ".png", png, 0});
        m.push_back({"Metadata/plate_no_light_" + n + ".png", png, 0});
        m.push_back({"Metadata/plate_" + n + "_small.png", png.substr(0, 200), 0});
        m.push_back({"Metadata/plate_" + n + ".gcode", plates[i]});
        m.push_back({"Metadata/plate_" + n + ".gcode.md5", gcode::archive::md5_hex(plates[i])});
    }
    m.push_back({"Metadata/model_settings.config", "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<config/>\n"});
    m.push_back({"Metadata/_rels/model_settings.config.rels", "<?xml version=\"1.0\"?>\n<Relationships/>\n"});
    for (std::size_t i = 0; i < plates.size(); ++i) {
        std::string n = std::to_string(i + 1);
        m.push_back({"Metadata/plate_" + n + ".json",
                     "{\"bbox_objects\":[{\"id\":" + n + ",\"name\":\"block.stl\"}],\"version\":2}"});
        m.push_back({"Metadata/pick_" + n + ".png", png, 0});
        m.push_back({"Metadata/top_" + n + ".png", png, 0});
    }
    m.push_back(
        {"Metadata/project_settings.config", "{\n    \"layer_height\": \"0.2\",\n    \"spiral_mode\": \"0\"\n}\n"});
    m.push_back({"Metadata/slice_info.config", bambu_slice_info(plates)});
    return m;
}

std::string pack(const std::vector<ZipMember>& members) {
    const std::string path =
        (std::filesystem::temp_directory_path() / ("scaffold-pack-" + std::to_string(::getpid()) + ".zip")).string();
    zipFile z = zipOpen64(path.c_str(), APPEND_STATUS_CREATE);
    if (!z) return {};
    for (const ZipMember& m : members) {
        zip_fileinfo zi{};
        zi.dosDate = 0x5B8A6000;  // 2025-12-10 12:00
        zi.external_fa = 0100644u << 16;
        zipOpenNewFileInZip64(z, m.name.c_str(), &zi, nullptr, 0, nullptr, 0, nullptr, m.method, m.method ? 6 : 0, 0);
        zipWriteInFileInZip(z, m.data.data(), static_cast<unsigned>(m.data.size()));
        const std::string chunk(1 << 20, '\0');
        for (std::uint64_t left = m.zeros; left > 0; left -= std::min<std::uint64_t>(left, chunk.size()))
            zipWriteInFileInZip(z, chunk.data(), static_cast<unsigned>(std::min<std::uint64_t>(left, chunk.size())));
        zipCloseFileInZip(z);
    }
    zipClose(z, nullptr);
    std::string bytes = load_file(path);
    std::filesystem::remove(path);
    return bytes;
}

std::vector<RawMember> unpack(const std::string& zip) {
    const std::string path =
        (std::filesystem::temp_directory_path() / ("scaffold-unpack-" + std::to_string(::getpid()) + ".zip")).string();
    write_file(path, zip);
    std::vector<RawMember> out;
    unzFile u = unzOpen64(path.c_str());
    bool ok = u != nullptr;
    for (int r = ok ? unzGoToFirstFile(u) : UNZ_END_OF_LIST_OF_FILE; ok && r == UNZ_OK; r = unzGoToNextFile(u)) {
        unz_file_info64 info{};
        char name[1024];
        ok = unzGetCurrentFileInfo64(u, &info, name, sizeof name, nullptr, 0, nullptr, 0) == UNZ_OK;
        RawMember m{name,
                    static_cast<int>(info.compression_method),
                    static_cast<std::uint32_t>(info.crc),
                    static_cast<std::uint32_t>(info.dosDate),
                    static_cast<std::uint32_t>(info.external_fa),
                    {},
                    {}};
        for (int raw : {1, 0}) {
            int method = 0, level = 0;
            ok = ok && unzOpenCurrentFile2(u, &method, &level, raw) == UNZ_OK;
            std::string& into = raw ? m.raw : m.data;
            char buf[65536];
            int n = 0;
            while (ok && (n = unzReadCurrentFile(u, buf, sizeof buf)) > 0)
                into.append(buf, static_cast<std::size_t>(n));
            ok = ok && n == 0 && unzCloseCurrentFile(u) == UNZ_OK;
        }
        out.push_back(std::move(m));
    }
    if (u) unzClose(u);
    std::filesystem::remove(path);
    if (!ok) out.clear();
    return out;
}

}  // namespace scaffold::testing
