#pragma once
// Included by main.cpp only (the one translation unit that sees CLI11).
//
// `rigid inertia <primitive> ...` and `rigid inertia check FILE`. A positional SOURCE that is
// not a subcommand name (e.g. a mesh file: `rigid inertia part.stl --density 2700`) reaches
// rigid::cli::run_inertia_source with the output options of the `inertia` command itself;
// a mesh source plugs in there (cmd_inertia.cpp) and adds its own options next to SOURCE.
#include <memory>

#include "cmd_inertia.hpp"
#include "cmd_inertia_fix.hpp"
#include "rigid/mass/primitive_table.hpp"
#include "rigid/scene/density_field.hpp"

/// --about, --frame, --format, --name, --output (shared by every inertia source).
inline void add_inertia_output_options(CLI::App* cmd, rigid::cli::InertiaOutputOptions& out) {
  cmd->add_option("--about", out.about,
                  "point the inertia is about: com, origin, or x,y,z in metres (urdf/mjcf/sdf: "
                  "the link origin is put at x,y,z)")
      ->default_str("com");
  cmd->add_option("--frame", out.frame, "body (the primitive's frame) or principal")
      ->default_str("body");
  cmd->add_option("--format", out.format, "text, json, urdf, mjcf, sdf, pseudo (4×4 pseudo-inertia) or "
                  "log-cholesky (its 10 parameters)")->default_str("text");
  cmd->add_option("--name", out.name, "link/body name in urdf/mjcf/sdf output")->default_str("body");
  cmd->add_option("-o,--output", out.output, "write to this file instead of standard output");
}

/// --axis, --origin, --rpy: where a primitive sits in the link frame.
inline void add_placement_options(CLI::App* cmd, rigid::cli::InertiaPrimitiveOptions& opts) {
  cmd->add_option("--axis", opts.axis,
                  "direction of the shape's own z axis in the link frame: x, y, z, -x, -y, -z or "
                  "vx,vy,vz (applied before --rpy)")
      ->default_str("z");
  cmd->add_option("--rpy", opts.rpy,
                  "then rotate by roll,pitch,yaw in radians (URDF: R = Rz(yaw) Ry(pitch) Rx(roll))")
      ->default_str("0,0,0");
  cmd->add_option("--origin", opts.origin,
                  "then put the shape's own origin (its centre; the cone's base centre) at x,y,z (m)")
      ->default_str("0,0,0");
}

/// `rigid inertia fix MODEL`: inertials recomputed from a URDF/SDF/MJCF model's geometry.
inline void add_inertia_fix_command(CLI::App* inertia) {
  auto fix = std::make_shared<rigid::cli::InertiaFixOptions>();
  auto* cmd = inertia->add_subcommand(
      "fix", "Recompute the inertials of a URDF, SDF or MJCF model from its geometry; only the "
             "<inertial> elements change");
  cmd->add_option("MODEL", fix->file, "URDF, SDF or MJCF file")->required();
  cmd->add_option("-o,--output", fix->output,
                  "write the fixed model here (nothing is written if a link cannot be fixed)");
  cmd->add_option_function<double>(
      "--density", [fix](double v) { fix->density = v; },
      "URDF/SDF: density of the geometry (kg/m³; default 1000 with a warning)");
  cmd->add_flag("--keep-mass", fix->keep_mass,
                "keep each link's stated mass and distribute it by the geometry");
  cmd->add_option("--from", fix->from, "URDF/SDF: collision or visual geometry")
      ->default_str("collision");
  cmd->add_option("--only", fix->only, "only these links/bodies")->expected(1, -1);
  cmd->add_option("--package-path", fix->package_paths,
                  "NAME=DIR: where package://NAME/ (and model://NAME/) meshes are")
      ->expected(1, -1);
  cmd->add_option("--format", fix->format, "table format: text or json")->default_str("text");
  cmd->callback([fix] { rigid::cli::run_inertia_fix(*fix); });
}

inline void add_inertia_command(CLI::App& app) {
  auto* inertia = app.add_subcommand(
      "inertia", "Mass properties of a primitive, or check the inertials of a URDF/MJCF/SDF file");
  inertia->require_subcommand(0, 1);

  // one subcommand per entry of the primitive catalogue, answering to its every name and alias
  // with '-' or '_'; one option per size, under every name of the size
  for (const auto& entry : rigid::mass::primitive_table()) {
    auto opts = std::make_shared<rigid::cli::InertiaPrimitiveOptions>();
    opts->primitive = entry.name;
    auto* cmd = inertia->add_subcommand(rigid::cli::cli_name(entry.name), entry.description);
    cmd->alias(entry.name);
    for (const auto& a : entry.aliases) {
      cmd->alias(rigid::cli::cli_name(a));
      if (a.find('_') != std::string::npos) cmd->alias(a);
    }
    for (const auto& size : entry.sizes) {
      std::string flags = "--" + rigid::cli::cli_name(size.name);
      if (size.name.find('_') != std::string::npos) flags += ",--" + size.name;
      for (const auto& a : size.aliases) {
        flags += ",--" + rigid::cli::cli_name(a);
        if (a.find('_') != std::string::npos) flags += ",--" + a;
      }
      cmd->add_option_function<double>(
          flags, [opts, key = size.name](double v) { opts->sizes[key] = v; }, size.help + " (" + size.unit + ")");
    }
    for (const auto& point : entry.points) {
      cmd->add_option_function<std::string>(
          "--" + point.name, [opts, key = point.name](const std::string& v) { opts->points[key] = v; },
          point.help + " as x,y,z (m)");
    }
    cmd->add_option_function<double>(
        "--mass", [opts](double v) { opts->mass = v; }, "mass (kg)");
    cmd->add_option_function<double>(
        "--density", [opts](double v) { opts->density = v; }, "density (" + entry.density_unit + ")");
    if (rigid::scene::takes_density_field(entry.name)) {
      cmd->add_option("--density-field", opts->density_field,
                      "density varying in space: an expression of x, y, z (m, the shape's own "
                      "frame) in kg/m³, integrated by adaptive cubature (its error estimate is "
                      "printed); instead of --mass/--density");
    }
    add_inertia_output_options(cmd, opts->output);
    add_placement_options(cmd, *opts);
    cmd->add_option("--tolerance", opts->tolerance,
                    "1σ of the inputs, propagated to first order: dims=±0.1mm, density=±2%, "
                    "mass=±5g, a size by name (radius=±0.05mm), vertices=±0.05mm (tetrahedron); "
                    "text and json only");
    cmd->callback([opts] { rigid::cli::run_inertia_primitive(*opts); });
  }

  auto check = std::make_shared<rigid::cli::InertiaCheckOptions>();
  auto* cmd = inertia->add_subcommand(
      "check", "Validate every <inertial> of a URDF, MJCF or SDF file (exit 1 if any is invalid)");
  cmd->add_option("FILE", check->file, "URDF, MJCF or SDF file")->required();
  cmd->callback([check] { rigid::cli::run_inertia_check(*check); });
  add_inertia_fix_command(inertia);

  // anything else: `rigid inertia SOURCE [options]` (mesh files plug in here)
  auto source = std::make_shared<rigid::cli::InertiaSourceOptions>();
  inertia->add_option("SOURCE", source->source, "a file with a body to measure (the primitives are the subcommands below)");
  add_inertia_output_options(inertia, source->output);
  inertia->add_option_function<double>(
      "--mass", [source](double v) { source->mass = v; }, "mesh files: total mass (kg)");
  inertia->add_option_function<double>(
      "--density", [source](double v) { source->density = v; },
      "mesh files: density (kg/m³; of the material with --shell, which then needs --thickness)");
  inertia->add_option_function<double>(
      "--areal-density", [source](double v) { source->areal_density = v; },
      "mesh files: a thin shell's mass per unit area (kg/m²; implies --shell, instead of "
      "--thickness and --density)")
      ->type_name("KG_PER_M2");
  inertia->add_option("--density-field", source->density_field,
                      "mesh files: a density varying in space, an expression of x, y, z (m, the "
                      "mesh's frame) in kg/m³ over the closed mesh, integrated by adaptive "
                      "cubature (its error estimate is printed); instead of --mass/--density")
      ->type_name("EXPR");
  inertia->add_option("--units", source->units, "mesh files: length unit m, cm, mm or in")
      ->default_str("m");
  inertia->add_flag("--shell", source->shell, "mesh files: a thin shell, not a solid");
  inertia->add_option_function<double>(
      "--thickness", [source](double v) { source->thickness = v; },
      "mesh files with --shell: wall thickness (m)");
  inertia->add_flag("--fill-holes", source->fill_holes,
                    "mesh files: close holes whose border is a simple loop before computing "
                    "(a planar hole is closed exactly)");
  inertia->add_option("--tolerance", source->tolerance,
                      "1σ of the inputs, propagated to first order (text and json only); mesh "
                      "files: of each vertex coordinate and of the amount, vertices=±0.05mm,"
                      "density=±2%; primitives take it after their name, e.g. `rigid inertia box "
                      "... --tolerance dims=±0.1mm` (see `rigid inertia box --help`)");
  // unknown words after an unknown SOURCE reach the callback, which names the real problem
  inertia->allow_extras();
  inertia->callback([inertia, source] {
    if (!inertia->get_subcommands().empty()) return;
    // no SOURCE at all is a usage error, as any missing argument (exit status 2)
    if (source->source.empty()) {
      throw CLI::RequiredError("SOURCE (a primitive subcommand, a mesh file or `check FILE`)");
    }
    rigid::cli::run_inertia_source(*source);
  });
}
