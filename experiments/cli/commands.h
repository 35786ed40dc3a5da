// The subcommands of `fairshape`, one function each (commands.cpp), kept apart from CLI11.
#pragma once

#include <string>
#include <vector>

#include "fairshape/experiment/sweep_runner.h"
#include "fairshape/render/figure.h"

namespace fairshape::cli {

struct InfoArgs { std::string mesh; };
struct ConvertArgs { std::string input, output; bool binary = false; };
// The inputs and the PNG are the positional files (the PNG last); the names are the
// NameTables' spellings, checked by cmd_render.
struct RenderArgs {
  std::vector<std::string> files;
  render::FigureSpec spec;
  std::string view = "iso", up = "y", component, map, background = "white";
  std::vector<double> range, focus;
  bool no_overlays = false;
};
struct SubdivideArgs {
  std::string input, output, scheme, boundary = "edge-only", weights = "loop", implementation = "optimized";
  int levels = 1;
  bool limit = false;
  double max_memory_gb = 8.0;
};

int cmd_info(const InfoArgs& a);
int cmd_convert(const ConvertArgs& a);
int cmd_render(const RenderArgs& a, int argc, char** argv);  // argv: to re-run under xvfb-run
int cmd_list();
int cmd_list_keys();
int cmd_schema(const std::string& output);  // "": standard output
int cmd_subdivide(const SubdivideArgs& a);
struct RemeshArgs {
  std::string input, output, scheme, boundary = "edge-only", weights = "loop";
  std::string base = "quad-dominant", base_method = "auto", fit = "level-by-level";  // RemeshOptions{}
  int base_faces = 500, levels = 3, relax_rounds = 4;
};
int cmd_remesh(const RemeshArgs& a);
struct EnergyArgs {
  std::string mesh, out, scheme = "catmull-clark", implementation = "optimized";
  double alpha = 0.1, beta = 1.0;
  int level = 0;
};
int cmd_energy(const EnergyArgs& a);

}  // namespace fairshape::cli
