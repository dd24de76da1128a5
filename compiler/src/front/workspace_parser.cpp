#include "sandpaper/compiler/workspace_parser.hpp"

#include "sandpaper/schema/input_limits.hpp"
#include "token_cursor.hpp"

#include <cmath>

namespace sandpaper::compiler {
namespace {

using schema::Dimension;

const std::vector<std::string>& workspace_keywords() {
  static const std::vector<std::string> k{"size", "patch"};
  return k;
}

class WorkspaceParser : TokenCursor {
 public:
  WorkspaceParser(const std::vector<Token>& tokens, std::shared_ptr<const SourceFile> file, Diagnostics& diags)
      : TokenCursor(tokens), file_(std::move(file)), diags_(diags) {}

  // workspace_file := End* 'workspace' STRING '{' (ws_statement? End)* '}' End* Eof
  WorkspaceSyntax file() {
    WorkspaceSyntax ws;
    ws.file = file_;
    skip_ends();
    if (!(peek().kind == TokenKind::Word && peek().text == "workspace")) {
      diags_.error("E0501", peek().location, "expected `workspace`, found " + describe(peek()),
                   "a workspace file is one block: workspace \"name\" { patch \"corduroy\" at 0 mm, 0 mm size 40 mm }");
      return ws;
    }
    next();
    if (peek().kind != TokenKind::String) {
      diags_.error("E0531", peek().location, "expected the workspace's name as a string, found " + describe(peek()),
                   "write workspace \"name\" { ... }");
    } else {
      ws.name = peek().text;
      ws.name_location = next().location;
    }
    const SourceLocation block_start = ws.name_location.file ? ws.name_location : peek().location;
    if (peek().kind != TokenKind::LBrace) {
      diags_.error("E0501", peek().location, "expected '{' after the workspace name, found " + describe(peek()),
                   "open the workspace's body with '{'");
      // Read the statements anyway so that their errors are reported too.
    } else {
      next();
    }
    statements(ws);
    if (peek().kind == TokenKind::RBrace) {
      next();
    } else {
      diags_.error("E0503", block_start, "the workspace block is not closed", "add '}' after its last patch");
      return ws;
    }
    skip_ends();
    if (peek().kind != TokenKind::Eof)
      diags_.error("E0504", peek().location, "text after the workspace block",
                   "a file holds one workspace; move this into the block or into a file of its own");
    return ws;
  }

 private:
  // (ws_statement? End)*   -- stops at '}' or the end of the file
  void statements(WorkspaceSyntax& ws) {
    while (true) {
      skip_ends();
      if (peek().kind == TokenKind::Eof || peek().kind == TokenKind::RBrace) return;
      try {
        statement(ws);
        const Token& t = peek();
        if (!(t.kind == TokenKind::End || t.kind == TokenKind::Eof || t.kind == TokenKind::RBrace)) {
          diags_.error("E0534", t.location, "unexpected " + describe(t) + " after the statement",
                       "put one statement on each line, or separate statements with ';'");
          throw StatementError{};
        }
      } catch (const StatementError&) {
        while (peek().kind != TokenKind::End && peek().kind != TokenKind::Eof && peek().kind != TokenKind::RBrace) next();
      }
    }
  }

  // ws_statement := size | patch
  void statement(WorkspaceSyntax& ws) {
    const Token& kw = peek();
    if (kw.kind != TokenKind::Word) {
      diags_.error("E0501", kw.location, "expected a workspace statement, found " + describe(kw),
                   "a workspace holds `size W x H` and `patch \"material\" at X, Y size W x H` lines");
      throw StatementError{};
    }
    if (kw.text == "size") {
      next();
      ws_size(ws, kw.location);
    } else if (kw.text == "patch") {
      next();
      ws.patches.push_back(patch(kw.location));
      if (ws.patches.size() == schema::limits::kMaxWorkspacePatches + 1)
        diags_.error("E0509", kw.location,
                     "more than " + std::to_string(schema::limits::kMaxWorkspacePatches) + " patches in one workspace",
                     "split the workspace into several, or tile one larger patch instead of many small ones");
    } else {
      const std::string guess = closest_match(kw.text, workspace_keywords());
      diags_.error("E0502", kw.location, "unknown workspace statement '" + kw.text + "'",
                   guess.empty() ? "a workspace holds `size` and `patch` statements" : "did you mean `" + guess + "`?");
      throw StatementError{};
    }
  }

  // size := 'size' LENGTH ['x' LENGTH]
  void ws_size(WorkspaceSyntax& ws, const SourceLocation& keyword) {
    if (ws.width) {
      auto& d = diags_.error("E0505", keyword, "the workspace size is given twice", "keep one of the two `size` lines");
      d.notes.push_back({ws.size_location, "the size is first given here"});
      throw StatementError{};
    }
    Quantity w = length("the workspace width");
    std::optional<Quantity> h;
    if (peek().kind == TokenKind::Word && peek().text == "x") {
      next();
      h = length("the workspace height");
    }
    positive(w, "workspace width");
    if (h) positive(*h, "workspace height");
    ws.width = w;
    ws.height = h;
    ws.size_location = keyword;
  }

  // patch := 'patch' STRING 'at' LENGTH ',' LENGTH ['size' LENGTH ['x' LENGTH]]
  PatchPlacementSyntax patch(const SourceLocation& keyword) {
    PatchPlacementSyntax p;
    p.location = keyword;
    if (peek().kind != TokenKind::String) {
      diags_.error("E0531", peek().location, "expected the patch's material as a quoted string, found " + describe(peek()),
                   "write patch \"corduroy\" (a library name), patch \"roughness 0.4; grating period 2 mm\" or "
                   "patch \"stone.hmat\", then at X, Y size W x H");
      throw StatementError{};
    }
    p.material = peek().text;
    p.material_location = next().location;
    if (p.material.find_first_not_of(" \t") == std::string::npos) {
      diags_.error("E0508", p.material_location, "the patch has an empty material",
                   "name a library entry (\"corduroy\"), write statements (\"roughness 0.4; grating period 2 mm\") "
                   "or give a .hmat file");
      throw StatementError{};
    }
    if (!(peek().kind == TokenKind::Word && peek().text == "at")) {
      diags_.error("E0532", peek().location, "expected `at` and the patch centre, found " + describe(peek()),
                   "write at X, Y with units, e.g. at -60 mm, 0 mm (the workspace centre is 0, 0)");
      throw StatementError{};
    }
    next();
    p.x = length("the patch centre's x");
    if (peek().kind != TokenKind::Comma) {
      diags_.error("E0532", peek().location, "expected ',' between the centre's x and y, found " + describe(peek()),
                   "write at X, Y, e.g. at -60 mm, 0 mm");
      throw StatementError{};
    }
    next();
    p.y = length("the patch centre's y");
    p.at_location = p.x.location;
    if (p.y.location.line == p.x.location.line)
      p.at_location.length = p.y.location.column + p.y.location.length - p.x.location.column;
    if (peek().kind == TokenKind::Word && peek().text == "size") {
      next();
      p.width = length("the patch width");
      if (peek().kind == TokenKind::Word && peek().text == "x") {
        next();
        p.height = length("the patch height");
      }
      positive(*p.width, "patch width");
      if (p.height) positive(*p.height, "patch height");
    }
    return p;
  }

  void positive(const Quantity& q, const char* what) {
    if (q.si > 0 && q.si >= schema::limits::kMinPlausibleLength_m && q.si <= schema::limits::kMaxPlausibleLength_m) return;
    if (q.si > 0)
      diags_.error("E0506", q.location, std::string("the ") + what + " " + q.text() + " is outside what a workspace program holds (1e-12 m to 1e12 m)",
                   "give a size a hand could feel, in mm");
    else
      diags_.error("E0506", q.location, std::string("the ") + what + " must be positive, not " + q.text(), "give a size greater than zero");
    throw StatementError{};
  }

  // LENGTH := NUMBER UNIT, UNIT a length unit (the material language's unit rules, E0203-E0205)
  Quantity length(const char* what) {
    const Dimension dim = Dimension::Length;
    const std::string units = schema::units_of(dim);
    const Token& n = peek();
    if (n.kind != TokenKind::Number) {
      diags_.error("E0533", n.location, std::string("expected ") + what + " (a number and a length unit), found " + describe(n),
                   "for example 40 mm");
      throw StatementError{};
    }
    next();
    const Token& u = peek();
    const auto def = u.kind == TokenKind::Word ? schema::find_unit(u.text) : std::nullopt;
    if (!def) {
      std::vector<std::string> names;
      for (const auto& x : schema::all_units()) names.emplace_back(x.name);
      const std::string guess = u.kind == TokenKind::Word ? closest_match(u.text, names) : std::string();
      if (guess.empty()) {
        diags_.error("E0203", n.location, "`" + n.text + "` has no unit; " + what + " is a length",
                     "add a unit: " + units + " (e.g. 40 mm)");
      } else {
        diags_.error("E0204", u.location, "unknown unit '" + u.text + "'", "did you mean `" + guess + "`?");
      }
      throw StatementError{};
    }
    if (def->dimension != dim) {
      diags_.error("E0205", u.location, "`" + u.text + "` is a " + std::string(schema::dimension_name(def->dimension)) +
                   " unit, but " + what + " is a length", "use one of: " + units);
      throw StatementError{};
    }
    next();
    if (!std::isfinite(n.number)) {
      diags_.error("E0103", n.location, "number out of range '" + n.text + "'", "use a finite number");
      throw StatementError{};
    }
    SourceLocation span = n.location;
    span.length = u.location.line == n.location.line ? u.location.column + u.location.length - n.location.column
                                                      : n.location.length;
    return Quantity{n.number, u.text, n.number * def->to_si, span};
  }

  std::shared_ptr<const SourceFile> file_;
  Diagnostics& diags_;
};

}  // namespace

WorkspaceSyntax parse_workspace(const std::vector<Token>& tokens, std::shared_ptr<const SourceFile> file,
                                Diagnostics& diags) {
  if (tokens.empty() || tokens.back().kind != TokenKind::Eof) throw InternalError("workspace tokens must end with Eof");
  return WorkspaceParser(tokens, std::move(file), diags).file();
}

}  // namespace sandpaper::compiler
