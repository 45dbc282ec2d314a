// limn-examples: writes the built-in example meshes (lib/mesh/examples.h) as OBJ files with UVs
// and tags, so the examples and tests need no input files. The bytes are the same on every run.
#include "base/cli.h"
#include "base/error.h"
#include "base/io.h"
#include "mesh/examples.h"
#include "mesh/obj.h"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <sstream>

using namespace limn;

int main(int argc, char** argv) {
    return cli::run("limn-examples", argc, argv, [](int ac, char** av) {
        cli::Common common;
        std::string dir = ".", only;
        bool list = false;
        std::vector<Example> examples = builtinExamples();
        std::string names;
        for (const auto& e : examples) {
            std::string file = e.name + ".obj";
            names += "  " + file + std::string(file.size() < 20 ? 20 - file.size() : 1, ' ') +
                     e.description + "\n";
        }
        cli::Parser parser("limn-examples", "[options] [-o DIR]",
                           "Writes the built-in example meshes as OBJ files (positions, UVs and\n"
                           "OpenSubdiv tags) into DIR, creating it if needed.",
                           common, /*hasOutput=*/false, /*hasDepfile=*/false);
        parser.text("-o, --output", "DIR", &dir, "directory to write the OBJ files into")
            .text("--only", "NAME[,NAME...]", &only,
                  "write only these examples [default: all of them]")
            .flag("--list", &list, "print the example names, one per line, and exit")
            .notes("Examples:\n" + names);
        if (!parser.parse(ac, av)) return 0;

        if (list) {
            for (const auto& e : examples) std::cout << e.name << "\n";
            return 0;
        }
        std::vector<const Example*> chosen;
        if (only.empty()) {
            for (const auto& e : examples) chosen.push_back(&e);
        } else {
            std::stringstream ss(only);
            std::string name;
            while (std::getline(ss, name, ',')) {
                auto it = std::find_if(examples.begin(), examples.end(),
                                       [&](const Example& e) { return e.name == name; });
                if (it == examples.end())
                    throw Error(ErrorKind::Usage,
                                "--only: no example named '" + name + "' (see --list)");
                chosen.push_back(&*it);
            }
        }
        std::error_code ec;
        std::filesystem::create_directories(dir, ec);
        if (ec) {
            Error e(ErrorKind::BadInput, "cannot create the directory: " + ec.message());
            e.setFile(dir);
            throw e;
        }
        for (const Example* e : chosen) {
            std::string path = (std::filesystem::path(dir) / (e->name + ".obj")).string();
            OutputFile out(path, OutputFile::Kind::Text);
            out.write("# limn-examples " + e->name + ": " + e->description + "\n");
            out.write(writeObj(e->mesh));
            out.commit();
            cli::info("wrote " + path);
        }
        return 0;
    });
}
