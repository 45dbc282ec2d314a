// limn-examples: writes the built-in example meshes (lib/mesh/examples.h) as OBJ files with UVs
// and tags, so the examples and tests need no input files. The bytes are the same on every run.
#include "base/cli.h"
#include "base/error.h"
#include "base/io.h"
#include "mesh/examples.h"
#include "mesh/obj.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

using namespace limn;

int main(int argc, char** argv) {
    return cli::run("limn-examples", argc, argv, [](int ac, char** av) {
        cli::Common common;
        std::string dir = ".", only;
        bool list = false, listSequences = false;
        std::vector<Example> examples = builtinExamples();
        std::vector<ExampleSequence> sequences = builtinSequences();
        std::string names;
        for (const auto& e : examples) {
            std::string file = e.name + ".obj";
            names += "  " + file + std::string(file.size() < 20 ? 20 - file.size() : 1, ' ') +
                     e.description + "\n";
        }
        names += "Animations (one folder of frames each, for limn-render --frames):\n";
        for (const auto& q : sequences) {
            std::string file = q.name + "/" + q.name + "_%04d.obj";
            names += "  " + file + std::string(file.size() < 20 ? 20 - file.size() : 1, ' ') +
                     q.description + "\n";
        }
        cli::Parser parser("limn-examples", "[options] [-o DIR]",
                           "Writes the built-in example meshes as OBJ files (positions, UVs and\n"
                           "OpenSubdiv tags) into DIR, creating it if needed.",
                           common, /*hasOutput=*/false, /*hasDepfile=*/false);
        parser.text("-o, --output", "DIR", &dir, "directory to write the OBJ files into")
            .text("--only", "NAME[,NAME...]", &only,
                  "write only these examples [default: all of them]")
            .flag("--list", &list, "print the example names, one per line, and exit")
            .flag("--list-sequences", &listSequences,
                  "print the animation names, one per line, and exit")
            .notes("Examples:\n" + names);
        if (!parser.parse(ac, av)) return 0;

        if (list || listSequences) {
            if (list)
                for (const auto& e : examples) std::cout << e.name << "\n";
            if (listSequences)
                for (const auto& q : sequences) std::cout << q.name << "\n";
            return 0;
        }
        std::vector<const Example*> chosen;
        std::vector<const ExampleSequence*> chosenSequences;
        if (only.empty()) {
            for (const auto& e : examples) chosen.push_back(&e);
            for (const auto& q : sequences) chosenSequences.push_back(&q);
        } else {
            std::stringstream ss(only);
            std::string name;
            while (std::getline(ss, name, ',')) {
                auto it = std::find_if(examples.begin(), examples.end(),
                                       [&](const Example& e) { return e.name == name; });
                auto sq = std::find_if(sequences.begin(), sequences.end(),
                                       [&](const ExampleSequence& q) { return q.name == name; });
                if (it != examples.end())
                    chosen.push_back(&*it);
                else if (sq != sequences.end())
                    chosenSequences.push_back(&*sq);
                else
                    throw Error(ErrorKind::Usage, "--only: no example named '" + name +
                                                      "' (see --list and --list-sequences)");
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
        for (const ExampleSequence* q : chosenSequences) {
            const std::filesystem::path folder = std::filesystem::path(dir) / q->name;
            std::filesystem::create_directories(folder, ec);
            if (ec) {
                Error e(ErrorKind::BadInput, "cannot create the directory: " + ec.message());
                e.setFile(folder.string());
                throw e;
            }
            for (size_t k = 0; k < q->frames.size(); ++k) {
                char file[64];
                std::snprintf(file, sizeof file, "%s_%04zu.obj", q->name.c_str(), k);
                OutputFile out((folder / file).string(), OutputFile::Kind::Text);
                out.write("# limn-examples " + q->name + " frame " + std::to_string(k) + " of " +
                          std::to_string(q->frames.size()) + ": " + q->description + "\n");
                out.write(writeObj(q->frames[k]));
                out.commit();
            }
            cli::info("wrote " + std::to_string(q->frames.size()) + " frames into " + folder.string());
        }
        return 0;
    });
}
