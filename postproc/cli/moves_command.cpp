// `vcpost moves PROGRAM`: the interpreted motion events, one per line, in
// the vocabulary of rs274's canonical transcript (see program/transcript.h).
#include <cstdio>
#include <iostream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "postproc/cldata/cl_reader.h"
#include "postproc/cli/commands.h"
#include "postproc/cli/interrupt.h"
#include "postproc/cli/klartext_programs.h"
#include "postproc/cli/number_options.h"
#include "postproc/cli/program_text.h"
#include "postproc/gcode/interpreter.h"
#include "postproc/heidenhain/interpreter.h"
#include "postproc/post/post_job.h"
#include "postproc/program/timing.h"
#include "postproc/program/transcript.h"

namespace vcpost::cli {

namespace {

// The events read before an error go out ahead of its message on stderr; a
// failed flush adds nothing to that error, which is the one reported.
void write_partial_transcript(std::string_view out) {
  write_standard_output(out);
  (void)std::fflush(stdout);
}

// Writes the transcript out once past 64 KB: memory stays flat with the
// program's length.
void flush_when_full(std::string& out) {
  if (out.size() > (1u << 16)) {
    write_standard_output(out);
    out.clear();
  }
}

}  // namespace

// APT CL data: the same events from the CL reader, printed the same way.
template <class Options>
void print_cl_moves(std::string_view text, const std::string& name,
                    const program::TranscriptOptions& print, const Options& options) {
  std::string copy(text);
  std::istringstream in(copy);
  cldata::ClReader reader(in, name);
  program::PathClock clock(program::TimingSettings{options.rapid_rate, 0.0});
  std::string out;
  program::Transcriber transcriber(print);
  std::uint64_t events = 0;
  try {
    while (auto event = reader.next()) {
      if (std::holds_alternative<program::CannedCycle>(*event)) continue;  // its moves follow
      ++events;
      clock.advance(*event);  // a feed move whose time is undefined fails, as in post
      if (!options.count) transcriber.append(out, *event);
    }
  } catch (const cldata::ClError& e) {
    write_partial_transcript(out);
    throw CommandError(e.vcpost::Error::code(), e.what());
  } catch (const program::TimingError& e) {
    write_partial_transcript(out);
    throw CommandError(e.code(), e.located(name));
  }
  write_standard_output(out);
  if (options.count) {
    std::printf("records %llu events %llu\n",
                static_cast<unsigned long long>(reader.record_count()),
                static_cast<unsigned long long>(events));
  }
  if (options.time) {
    std::printf("# program time %.4f s (rapids at %.0f mm/min)\n", clock.elapsed(),
                options.rapid_rate);
  }
  for (const auto& w : reader.warnings()) std::cerr << cldata::format(w, name) << '\n';
}

// The end of a G-code or Klartext listing: the rest of the transcript,
// then the counts (--count) and the programmed time (--time).
template <class Options>
void end_listing(const std::string& out, std::uint64_t lines, std::uint64_t events,
                 const program::PathClock& clock, const Options& options) {
  write_standard_output(out);
  if (options.count)
    std::printf("lines %llu events %llu\n", static_cast<unsigned long long>(lines),
                static_cast<unsigned long long>(events));
  if (options.time)
    std::printf("# program time %.4f s (rapids at %.0f mm/min)\n", clock.elapsed(),
                options.rapid_rate);
  finish_standard_output();
}

// Heidenhain Klartext: the same events from the Klartext reader.
template <class Options>
void print_klartext_moves(const ProgramText& text, const std::string& name,
                          const program::TranscriptOptions& print, const Options& options) {
  heidenhain::Interpreter interpreter(text.view());
  interpreter.set_program_loader(klartext_program_files(options.program));
  std::vector<program::Event> events;
  std::string out;
  std::uint64_t event_count = 0;
  auto show_warnings = [&] {
    for (const auto& w : interpreter.warnings())
      std::cerr << printable(heidenhain::format(w, name)) << '\n';
    if (interpreter.warning_count() > interpreter.warnings().size())
      std::cerr << name << ": " << interpreter.warning_count() - interpreter.warnings().size()
                << " more warnings not shown\n";
  };
  program::PathClock clock(program::TimingSettings{options.rapid_rate, 0.0});
  program::Transcriber transcriber(print);
  try {
    while (interpreter.next(events)) {
      for (const auto& e : events) {
        if (std::holds_alternative<program::CannedCycle>(e)) continue;  // its moves follow
        ++event_count;
        clock.advance(e);  // a feed move whose time is undefined fails, as in post
        if (!options.count) transcriber.append(out, e);
      }
      flush_when_full(out);
      events.clear();
    }
  } catch (const program::TimingError& e) {
    write_partial_transcript(out);
    show_warnings();
    throw CommandError(e.code(), e.located(name));
  } catch (const heidenhain::KlartextError& e) {
    write_partial_transcript(out);
    show_warnings();
    throw CommandError(e.vcpost::Error::code(), heidenhain::format(e.diagnostic(), name));
  }
  end_listing(out, interpreter.lines_read(), event_count, clock, options);
  show_warnings();
}

// G-code: the interpreter's events, the text behind it released as it goes.
template <class Options>
void print_gcode_moves(ProgramText& text, const std::string& name,
                       const program::TranscriptOptions& print, const Options& options,
                       const gcode::Dialect& dialect) {
  gcode::Interpreter interpreter(text.view(), dialect);
  std::vector<program::Event> events;
  std::string out;
  std::uint64_t event_count = 0;
  std::size_t warnings_shown = 0;
  auto flush_warnings = [&] {
    const auto& w = interpreter.warnings();
    for (; warnings_shown < w.size(); ++warnings_shown)
      std::cerr << printable(gcode::format(w[warnings_shown], name)) << '\n';
    if (interpreter.warning_count() > w.size())
      std::cerr << name << ": " << interpreter.warning_count() - w.size()
                << " more warnings not shown\n";
  };
  program::PathClock clock(program::TimingSettings{options.rapid_rate, 0.0});
  program::Transcriber transcriber(print);
  try {
    while (interpreter.next(events)) {
      event_count += events.size();
      // A feed move whose time is undefined (no feed, G95 with the spindle
      // stopped) fails here as it does in post (E6101-E6103).
      for (const auto& e : events) clock.advance(e);
      text.release_before(interpreter.block().offset);
      if (!options.count) {
        for (const auto& e : events) transcriber.append(out, e);
        flush_when_full(out);
      }
      events.clear();
    }
  } catch (const program::TimingError& e) {
    write_partial_transcript(out);
    flush_warnings();
    throw CommandError(e.code(), e.located(name));
  } catch (const gcode::GcodeError& e) {
    write_partial_transcript(out);
    flush_warnings();
    throw CommandError(e.code(), gcode::format(e.diagnostic(), name));
  }
  end_listing(out, interpreter.lines_read(), event_count, clock, options);
  flush_warnings();
}

void add_moves_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "moves", "Print the interpreted motion events in rs274's canonical-transcript vocabulary");
  struct Options {
    std::string program;
    std::string dialect = "rs274ngc";
    bool source = false;
    bool count = false;
    bool time = false;
    double rapid_rate = program::TimingSettings{}.rapid_mm_per_min;
  };
  auto options = std::make_shared<Options>();
  cmd->add_option("PROGRAM", options->program, "G-code or APT CL program ('-' for stdin)")
      ->required();
  cmd->add_option("--dialect", options->dialect,
                  "rs274ngc | fanuc (iso) | mazak (eia) | sinumerik (840d) | heidenhain "
                  "(klartext, tnc; Klartext is also recognised by its BEGIN PGM)")
      ->capture_default_str();
  cmd->add_flag("--source", options->source, "append file:line:col to every line");
  cmd->add_flag("--count", options->count,
                "print only the number of lines read and events (parse speed runs)");
  cmd->add_flag("--time", options->time,
                "end with the programmed time along the path (feed, rapids, dwells; no "
                "acceleration)");
  cmd->add_option("--rapid-rate", options->rapid_rate, "rapid traverse rate for --time, mm/min")
      ->capture_default_str()
      ->check(positive_number());
  cmd->callback([options] {
    standard_output_is_the_only_output();
    const auto dialect = gcode::dialect_from_name(options->dialect);
    if (!dialect) throw CommandError("moves: unknown dialect '" + options->dialect + "'");
    ProgramText text(options->program);
    const std::string name = options->program == "-" ? "<stdin>" : options->program;
    const program::TranscriptOptions print{options->source, name};
    const post::ProgramKind kind = post::program_kind(text.view(), *dialect);
    if (kind == post::ProgramKind::cldata) {
      print_cl_moves(text.view(), name, print, *options);
      return;
    }
    if (kind == post::ProgramKind::heidenhain) {
      print_klartext_moves(text, name, print, *options);
      return;
    }
    print_gcode_moves(text, name, print, *options, *dialect);
  });
}

}  // namespace vcpost::cli
