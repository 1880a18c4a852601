// fabmesh run DESIGN... [-o OUTDIR/ | -o FILE.ext | -o -] [-D path=value]... [--json]: the main job.

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <thread>

#include "geometry/core/errors.h"
#include "geometry/core/units.h"
#include "io/file.h"
#include "pipeline/cli/commands.h"
#include "pipeline/cli/run_progress.h"
#include "pipeline/failure.h"
#include "pipeline/job.h"
#include "pipeline/load_design.h"
#include "pipeline/output_table.h"
#include "pipeline/pictures.h"
#include "pipeline/report.h"
#include "pipeline/summary.h"

namespace fabmesh::cli {
namespace {

namespace fs = std::filesystem;

struct RunArgs {
  std::vector<std::string> designs;
  std::vector<std::string> defines;
  std::string out = "out";
  std::string export_units;
  std::string export_format;
  std::string report;  ///< --report FILE.html
  bool json = false;
  bool watch = false;  ///< --watch: run again whenever a design or a file it reads changes
};

// One design's outcome: a result, or the exit code and message of its failure.
struct Outcome {
  std::optional<Design> design;
  std::optional<Result> report;
  std::optional<EncodedJob> streamed;  ///< `-o -`: the job's bytes go to standard output
  std::optional<Failure> failure;
  int code() const { return failure ? failure->exit_code : kExitOk; }
};

void fail_with(Outcome& o, const std::string& subject) {
  o.failure = describe_failure(std::current_exception(), subject);
}

// The output formats' names, "stl, drc, ...", in the output table's order.
std::string format_names() {
  std::string names;
  for (const OutputFormat& f : output_formats())
    names += std::string(names.empty() ? "" : ", ") + std::string(f.name);
  return names;
}

// Where `-o` sends the outputs: a folder, one file (format by its ending), or standard output.
JobOptions output_options(const RunArgs& args) {
  JobOptions options;
  if (!args.export_units.empty()) options.export_units = args.export_units;
  if (!args.export_format.empty()) options.export_format = args.export_format;
  const std::string& out = args.out;
  std::error_code ec;
  const bool folder = out.back() == '/' || fs::is_directory(out, ec);
  if (out == "-" || (!folder && format_of_file(out) != nullptr)) {
    if (args.designs.size() != 1) {
      throw InputError(
          fmt::format("-o {}: a single output file takes a single design ({} given); use -o DIR/", out,
                      args.designs.size()));
    }
    if (out != "-" && !options.export_format) options.export_format = std::string(format_of_file(out)->name);
    options.output_file = out;
    options.out_dir = ".";
    return options;
  }
  if (!folder && names_a_file(out)) {
    // Never a folder named like a file: say which endings fabmesh writes.
    std::string endings;
    for (const OutputFormat& f : output_formats()) {
      if (f.file_suffix.find("PART") != std::string_view::npos) continue;  // one file per mould part
      endings += (endings.empty() ? "" : ", ") + std::string(f.file_suffix);
    }
    throw InputError(fmt::format(
        "-o {}: fabmesh writes no '{}' files; -o FILE takes one of these endings (in any case): {}; for a "
        "folder of that name write -o {}/",
        out, fs::path(out).extension().string(), endings, out));
  }
  options.out_dir = out;
  return options;
}

// Two designs with one name would overwrite each other's files.
void require_unique_names(std::vector<Outcome>& outcomes, const RunArgs& args) {
  std::map<std::string, std::size_t> first;
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    if (!outcomes[i].design) continue;
    const std::string& name = outcomes[i].design->common.name;
    const auto [it, fresh] = first.emplace(name, i);
    if (fresh) continue;
    throw InputError(
        fmt::format("{} and {} are both named '{}': their files would overwrite each other in {}; "
                    "give one another `name:` (nothing was run)",
                    args.designs[it->second], args.designs[i], name, args.out));
  }
}

// Two designs whose outputs resolve to one file (`name: x` with glb_draco and
// `name: x.draco` with glb both write x.draco.glb) would lose one of them.
void require_distinct_files(const std::vector<Outcome>& outcomes, const JobOptions& options,
                            const RunArgs& args) {
  std::map<std::string, std::pair<std::size_t, std::string>> first;  // path -> design, format
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    if (!outcomes[i].design) continue;
    std::vector<PlannedFile> files;
    try {
      files = planned_files(*outcomes[i].design, plan_job(*outcomes[i].design, options));
    } catch (const InputError&) {
      continue;  // a bad `outputs` entry: that design's job reports it
    }
    for (const PlannedFile& f : files) {
      const std::string path = fs::path(f.path).lexically_normal().string();
      const auto [it, fresh] = first.emplace(path, std::make_pair(i, f.format));
      if (fresh || it->second.first == i) continue;
      throw InputError(fmt::format(
          "{} ({} output) and {} ({} output) would both write {}: one file would be lost; give one "
          "another `name:` (nothing was run)",
          args.designs[it->second.first], it->second.second, args.designs[i], f.format, path));
    }
  }
}

// The HTML page of `--report`: one row per design, its preview and plot linked from the output folder.
void write_report(const RunArgs& args, const std::vector<Outcome>& outcomes) {
  const std::string base = fs::path(args.report).parent_path().string();
  HtmlReport page;
  page.title = "fabmesh run";
  page.generated_by = std::string("fabmesh ") + FABMESH_VERSION + " run --report";
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    const Outcome& o = outcomes[i];
    if (!o.report) {
      const std::string name = fs::path(args.designs[i]).stem().string();
      page.rows.push_back(report_row(failed_facts(name, o.code(), failure_line(*o.failure)), base));
      continue;
    }
    ReportRow row = report_row(item_facts(*o.report), base);
    for (std::size_t k = 0; k < o.report->files.size(); ++k) {
      const OutputFile& f = o.report->files[k];
      if (f.format == "png") row.preview_png = row.files[k];
      if (f.format == "plot") row.plot_svg = row.files[k];
    }
    page.rows.push_back(std::move(row));
  }
  if (!base.empty()) fs::create_directories(base);
  write_file_atomically(args.report, render_report_html(page));
}

// `watched`, when given, receives the files the run read: the designs and
// the files they reference (for --watch).
int run_designs(const RunArgs& args, Streams io, std::vector<std::string>* watched = nullptr) {
  JobOptions options = output_options(args);
  if (!args.report.empty()) {
    if (fs::path(args.report).extension() != ".html")
      throw InputError(fmt::format("--report {}: the report is an HTML page; name it *.html", args.report));
    // The report shows each design's preview and plot: written beside its other outputs.
    if (!options.output_file) options.also_formats = {"png", "plot"};
  }
  const std::vector<Override> overrides = parse_overrides(args.defines);
  const bool to_stdout = options.output_file && *options.output_file == "-";
  std::vector<Outcome> outcomes(args.designs.size());
  // Read every design first: a bad one, or two with one name, stops nothing that ran.
  tbb::parallel_for(std::size_t{0}, args.designs.size(), [&](std::size_t i) {
    try {
      outcomes[i].design = load_design(args.designs[i], overrides);
    } catch (...) {
      fail_with(outcomes[i], args.designs[i]);
    }
  });
  if (watched != nullptr) {
    *watched = args.designs;
    for (const Outcome& o : outcomes) {
      if (o.design)
        watched->insert(watched->end(), o.design->common.inputs.begin(), o.design->common.inputs.end());
    }
  }
  require_unique_names(outcomes, args);
  require_distinct_files(outcomes, options, args);
  std::optional<RunProgress> progress;
  if (io.verbosity > 0) {
    const bool terminal = &io.err == &std::cerr && ::isatty(STDERR_FILENO) == 1;
    progress.emplace(io.err, args.designs.size(), terminal);
  }
  // Jobs are pure functions of their designs: they run in parallel.
  tbb::parallel_for(std::size_t{0}, args.designs.size(), [&](std::size_t i) {
    Outcome& o = outcomes[i];
    if (!o.design) return;
    JobOptions job = options;
    if (progress) {
      job.on_stage = [&progress, name = o.design->common.name](const std::string& stage, double ms) {
        progress->stage(name, stage, ms);
      };
    }
    try {
      if (to_stdout) {
        auto [result, encoded] = prepare_job(*o.design, job);
        o.report = std::move(result);
        o.streamed = std::move(encoded);
      } else {
        o.report = run_job(*o.design, job);
      }
    } catch (...) {
      fail_with(o, args.designs[i]);
    }
    if (progress) progress->design_done();
  });
  if (progress) progress->finish();
  // With -o - the file is the standard output: reports go to the error stream.
  std::ostream& report_out = to_stdout ? io.err : io.out;
  int code = 0;
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    const Outcome& o = outcomes[i];
    code = std::max(code, o.code());
    if (o.failure) io.err << failure_line(*o.failure) << "\n";
    if (o.streamed) {
      for (const EncodedFile& f : o.streamed->files)
        io.out.write(f.encoded.bytes.data(), static_cast<std::streamsize>(f.encoded.bytes.size()));
    }
    if (args.json) {
      all.push_back(o.report ? design_item(args.designs[i], *o.report)
                             : error_item("design", args.designs[i], *o.failure));
    } else if (o.report && io.verbosity > 0) {
      print_summary(*o.report, report_out);
      if (io.verbosity > 1) {
        for (const auto& [stage, ms] : o.report->timings_ms)
          report_out << fmt::format("    {} {:.2f} ms\n", stage, ms);
      }
    }
    // Warnings go to the error stream, whatever the report's form.
    if (o.report && (args.json || io.verbosity > 0)) print_warnings(*o.report, args.designs[i], io.err);
  }
  // `run --json` prints an array always: one entry per design, whatever their number.
  if (args.json) print_json_items(all, report_out);
  if (!args.report.empty()) {
    write_report(args, outcomes);
    if (io.verbosity > 0 && !args.json) report_out << fmt::format("report: {}\n", args.report);
  }
  return code;
}

// --watch ends on SIGINT or SIGTERM: the handler only sets this flag, which
// the watch loop reads between runs (a run in progress completes).
volatile std::sig_atomic_t stop_watching = 0;

extern "C" void on_stop_signal(int /*signal*/) { stop_watching = 1; }

// What a watched file looks like on disk: a change of any of these is an edit.
struct FileStamp {
  bool exists = false;
  fs::file_time_type modified{};
  std::uintmax_t size = 0;
  bool operator==(const FileStamp& o) const {
    return exists == o.exists && modified == o.modified && size == o.size;
  }
};

std::vector<FileStamp> stamps_of(const std::vector<std::string>& files) {
  std::vector<FileStamp> out;
  for (const std::string& f : files) {
    std::error_code ec;
    FileStamp s;
    s.modified = fs::last_write_time(f, ec);
    s.exists = !ec;
    if (s.exists) s.size = fs::file_size(f, ec);
    out.push_back(s);
  }
  return out;
}

// The first of `files` whose stamp differs from `before`, or "".
std::string changed_file(const std::vector<std::string>& files, const std::vector<FileStamp>& before) {
  const std::vector<FileStamp> now = stamps_of(files);
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (!(now[i] == before[i])) return files[i];
  }
  return "";
}

// Runs the designs, then again each time one of them or a file one reads
// changes, until SIGINT/SIGTERM. A run that fails prints its error and
// writes nothing, so the last good files stay. Returns 0 when stopped.
int watch_designs(const RunArgs& args, Streams io) {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;  // no SA_RESTART: a sleep ends at once
  sigemptyset(&action.sa_mask);
  struct sigaction old_int {
  }, old_term{};
  sigaction(SIGINT, &action, &old_int);
  sigaction(SIGTERM, &action, &old_term);
  stop_watching = 0;
  std::vector<std::string> watched;
  auto run_once = [&] {
    watched.clear();
    int code = kExitInternal;
    try {
      code = run_designs(args, io, &watched);
    } catch (...) {
      const Failure failure = describe_failure(std::current_exception());
      io.err << failure_line(failure) << "\n";
      code = failure.exit_code;
    }
    if (watched.empty()) watched = args.designs;
    io.out << fmt::format("fabmesh: {}; watching {} file{} (Ctrl-C ends)\n",
                          code == kExitOk ? "done" : "failed, the last good files stay", watched.size(),
                          watched.size() == 1 ? "" : "s");
    io.out.flush();
  };
  run_once();
  std::vector<FileStamp> seen = stamps_of(watched);
  while (stop_watching == 0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    std::string changed = changed_file(watched, seen);
    if (changed.empty()) continue;
    // An editor may write a file in several steps: wait until it holds still.
    for (std::vector<FileStamp> now = stamps_of(watched); stop_watching == 0;) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      const std::vector<FileStamp> later = stamps_of(watched);
      if (later == now) break;
      now = later;
    }
    if (stop_watching != 0) break;
    io.out << fmt::format("fabmesh: {} changed; running again\n", changed);
    run_once();
    seen = stamps_of(watched);
  }
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);
  io.out << "fabmesh: stopped watching\n";
  return kExitOk;
}

// Where the example designs are, from the folder of the running program:
// FABMESH_EXAMPLES_FROM_PROGRAM (relative: "../share/fabmesh/examples" for an
// installed bin/fabmesh; the build puts a copy at the same place from
// build/pipeline/fabmesh). Empty when the program's own path is unknown.
fs::path examples_folder() {
  std::error_code ec;
  const fs::path program = fs::read_symlink("/proc/self/exe", ec);
  if (ec || program.empty()) return {};
  return (program.parent_path() / FABMESH_EXAMPLES_FROM_PROGRAM).lexically_normal();
}

constexpr const char* kBundledExample = "vessel_golden_shell.yaml";

}  // namespace

Runner add_run_command(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand("run", "Build, validate and write the meshes of design files");
  cmd->add_option("designs", args->designs, "Design files (YAML)")->required();
  cmd->add_option(
      "-o,--output", args->out,
      "Where to write: a folder (default: out; a trailing / or an existing folder), one file whose "
      "ending picks the format (x.stl, x.3mf, x.glb, x.draco.glb, ...: one design only), or - for "
      "standard output (one design, one format)");
  cmd->add_option("--export-format", args->export_format,
                  "Write only this format, whatever the design's outputs (" + format_names() + ")");
  cmd->add_option("--export-units", args->export_units,
                  "Unit of the files that carry none (STL, OBJ, PLY, OFF, Draco) and of 3MF, instead of the "
                  "design's export_units (default mm)")
      ->check(CLI::IsMember(length_unit_names()));
  cmd->add_flag("--json", args->json, "Print the JSON reports (an array, one entry per design)");
  cmd->add_option("--report", args->report,
                  "Also write an HTML report (one self-contained page: summary table, each design's preview "
                  "and plot, verdict, measures and files; the pictures are written with the outputs)");
  cmd->add_flag("--watch", args->watch,
                "Run again whenever a design or a file it reads (DXF, CSV) changes, printing the verdict; a "
                "design that breaks prints its error and keeps the last good files. Ctrl-C ends it");
  add_define_option(cmd, args->defines);
  return [args](Streams io) {
    if (!args->watch) return run_designs(*args, io);
    if (args->out == "-") throw InputError("--watch writes files again and again; it cannot write to -o -");
    return watch_designs(*args, io);
  };
}

int run_bundled_example(Streams io) {
  const fs::path folder = examples_folder();
  const fs::path example = folder / kBundledExample;
  std::error_code ec;
  if (folder.empty() || !fs::is_regular_file(example, ec)) {
    io.err << fmt::format(
        "fabmesh: no design given, and the bundled example is not at {} (fabmesh looks for its examples "
        "at {} from its own folder); give a design: fabmesh run DESIGN.yaml\n",
        folder.empty() ? std::string(kBundledExample) : example.string(), FABMESH_EXAMPLES_FROM_PROGRAM);
    return 2;
  }
  RunArgs args;
  args.designs = {example.string()};
  io.out << fmt::format("fabmesh: no design given; running the bundled example {}\n", args.designs[0]);
  const int code = run_designs(args, io);
  if (code == 0) {
    io.out << fmt::format("Files are in {}/. Try `fabmesh run --help` and the designs in {}.\n",
                          fs::absolute(args.out).string(), folder.string());
  }
  return code;
}

}  // namespace fabmesh::cli
