#!/usr/bin/env python3
"""Checks README.md and docs/**/*.md against the repository and the tools.

    check_docs.py --repo DIR [--capture EXE] [--viewer EXE] [--sweep EXE] [--compare EXE]
    check_docs.py --self-test --capture EXE --sweep EXE --compare EXE [--viewer EXE]

1. Links. Every relative link, [text](path), [text](path#anchor), ![alt](path) and
   reference definitions "[id]: path", outside code, must name a file or folder inside the
   repository (relative to the page; "/path" is relative to the repository root). An anchor
   into a Markdown page (or "#anchor" alone: this page) must be one of that page's headings,
   slugged as GitHub does, or an explicit <a name/id>. http(s):, mailto: and other schemes
   are not checked.

2. Flags. Every --flag the docs give avsm-capture, avsm-viewer, avsm-sweep or avsm-compare
   must appear in that tool's --help. A flag is given to a tool in one of two ways:

   a. On a command line: a line of a shell code block (``` with no language, sh, bash,
      shell, console, text) or an inline `code span`. A command starts at the start of the
      line or span, after "$ " (a prompt) and after a separator word (|, ||, &&, ;). Its
      command word is its first word after VAR=value words and the wrappers env, time,
      timeout N, sudo, exec, nice and xvfb-run (with their -options). When the command word
      is a tool (avsm-capture, or a path ending in /avsm-capture; tools/capture.sh is
      avsm-capture, whose extra arguments it passes on), every --flag up to the next
      separator belongs to that tool; flags of any other command (cmake, ctest, sbatch,
      host_embed, bench scripts, ...) are not checked. A tool named as an argument of
      another program (bench/viewer/frames_in_flight.py build/tools/avsm-viewer) is not
      its command. In a code block, shell comments (# ...) are dropped, and a line that
      ends in "\" or a next line that starts with --flag continues the command. For a
      value-taking flag (its --help shows "--flag VALUE") a value that looks like a flag is
      skipped: `avsm-sweep slurm --sbatch-arg --account=x` checks --sbatch-arg only.
      avsm-sweep has sub-commands: the word after avsm-sweep must be one of those its --help
      lists ("avsm-sweep run ...") and a flag must be in that sub-command's part of the
      help (the usage line and its indented continuation lines); without a sub-command a
      flag may be any sub-command's.

   b. In prose: a flag in a code span that starts with --flag (`--report writes`), or in
      plain text, belongs to the tool PROSE_RULES gives for its page and section (the
      nearest enclosing heading that has a rule, else the page's rule). Prose flags
      elsewhere are not checked: there, write the tool name in the span
      (`avsm-capture --compare-to uncompressed`).

   --help is always accepted. A tool whose executable is not given is skipped with a note
   (avsm-viewer exists only with -DAVSM_BUILD_VIEWER=ON).

Exit status 0: all good; 1: problems, one line each as FILE:LINE: message; 2: bad usage.
Standard library only.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile
import unicodedata
import urllib.parse

TOOLS = ("avsm-capture", "avsm-viewer", "avsm-sweep", "avsm-compare")

# Prose flags: page -> {section heading text (None: the whole page): "tool [sub-command]"}.
PROSE_RULES = {
    "docs/captures.md": {None: "avsm-capture"},
    "docs/viewer.md": {None: "avsm-viewer"},
    "docs/shadows.md": {None: "avsm-capture"},
    "docs/devices.md": {"At the device's limits": "avsm-capture"},
    "docs/farm.md": {"Running a sweep here": "avsm-sweep run", "Sweep report": "avsm-sweep report",
                     "Regression gate": "avsm-compare"},
}

SHELL_LANGUAGES = {"", "sh", "bash", "shell", "console", "text"}
SEPARATORS = {"|", "||", "&&", ";"}
WRAPPERS = {"env", "time", "sudo", "exec", "nice", "xvfb-run", "timeout"}
FLAG = re.compile(r"(?<![A-Za-z0-9_-])--[A-Za-z0-9][A-Za-z0-9_-]*")
SCHEME = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]*:")


# ---------------------------------------------------------------- the Markdown, roughly

class Page:
    """A Markdown file cut into fenced code blocks and the rest (text with code spans)."""

    def __init__(self, path, rel):
        self.path, self.rel = path, rel
        with open(path, encoding="utf-8") as f:
            self.text = f.read()
        self.lines = self.text.split("\n")
        self.blocks = []  # (language, [(line number, line)])
        self.prose = []   # (line number, line) outside fenced code
        fence = None
        for number, line in enumerate(self.lines, 1):
            m = re.match(r"^\s*(```+|~~~+)\s*([\w+-]*)", line)
            if fence is None and m:
                fence = m.group(1)
                self.blocks.append((m.group(2).lower(), []))
            elif fence is not None and line.strip().startswith(fence):
                fence = None
            elif fence is not None:
                self.blocks[-1][1].append((number, line))
            else:
                self.prose.append((number, line))
        # The prose as one text (code lines blanked, so offsets keep their line numbers).
        in_code = set(n for _, lines in self.blocks for n, _ in lines)
        kept = ["" if (n + 1) in in_code or re.match(r"^\s*(```|~~~)", l) else l for n, l in enumerate(self.lines)]
        self.prose_text = "\n".join(kept)
        self.line_starts = [0]
        for l in kept:
            self.line_starts.append(self.line_starts[-1] + len(l) + 1)

    def line_of(self, offset):
        lo, hi = 0, len(self.line_starts) - 1
        while lo < hi:
            mid = (lo + hi + 1) // 2
            if self.line_starts[mid] <= offset:
                lo = mid
            else:
                hi = mid - 1
        return lo + 1

    def code_spans(self):
        """(offset, content) of every inline code span of the prose; spans do not cross blank lines."""
        spans = []
        for m in re.finditer(r"(`+)(.+?)(?<!`)\1(?!`)", self.prose_text, re.S):
            if "\n\n" in m.group(2):
                continue
            spans.append((m.start(), m.end(), m.group(2).strip()))
        return spans

    def prose_without_code(self):
        """The prose with code spans blanked to spaces (offsets and newlines kept)."""
        chars = list(self.prose_text)
        for start, end, _ in self.code_spans():
            for i in range(start, end):
                if chars[i] != "\n":
                    chars[i] = " "
        return "".join(chars)

    def headings(self):
        """(line number, level, text) of the ATX headings outside code."""
        out = []
        for number, line in self.prose:
            m = re.match(r"^(#{1,6})\s+(.*?)\s*#*\s*$", line)
            if m:
                out.append((number, len(m.group(1)), m.group(2)))
        return out


def github_slug(heading):
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # links: their text
    text = re.sub(r"<[^>]+>", "", text).replace("`", "")
    text = text.strip().lower()
    kept = []
    for ch in text:
        if ch in " -_" or unicodedata.category(ch)[0] in "LMN":
            kept.append(ch)
    return "".join(kept).replace(" ", "-")


def anchors_of(page):
    seen, anchors = {}, set()
    for _, _, text in page.headings():
        slug = github_slug(text)
        n = seen.get(slug, 0)
        seen[slug] = n + 1
        anchors.add(slug if n == 0 else "%s-%d" % (slug, n))
    for m in re.finditer(r"<a\s+(?:name|id)=\"([^\"]+)\"", page.text):
        anchors.add(m.group(1))
    return anchors


# ---------------------------------------------------------------- links

def check_links(page, repo, problems, page_cache, counts):
    text = page.prose_without_code()
    targets = []
    for m in re.finditer(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]*)>?(?:\s+\"[^\"]*\")?\s*\)", text):
        targets.append((page.line_of(m.start()), m.group(1)))
    for m in re.finditer(r"(?m)^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s|$)", text):
        targets.append((page.line_of(m.start()), m.group(1)))
    for line, target in targets:
        if not target or SCHEME.match(target):
            continue  # http:, https:, mailto:, ...
        counts["links"] += 1
        path_part, _, anchor = target.partition("#")
        path_part = urllib.parse.unquote(path_part)
        if path_part:
            base = repo if path_part.startswith("/") else os.path.dirname(page.path)
            resolved = os.path.normpath(os.path.join(base, path_part.lstrip("/")))
            if os.path.relpath(resolved, repo).startswith(".."):
                problems.append("%s:%d: link '%s' leaves the repository" % (page.rel, line, target))
                continue
            if not os.path.exists(resolved):
                problems.append("%s:%d: broken link '%s': %s does not exist" %
                                (page.rel, line, target, os.path.relpath(resolved, repo)))
                continue
        else:
            resolved = page.path
        if anchor and resolved.endswith(".md") and os.path.isfile(resolved):
            if resolved not in page_cache:
                page_cache[resolved] = Page(resolved, os.path.relpath(resolved, repo))
            if anchor not in anchors_of(page_cache[resolved]):
                problems.append("%s:%d: broken link '%s': %s has no heading with anchor #%s" %
                                (page.rel, line, target, os.path.relpath(resolved, repo), anchor))


# ---------------------------------------------------------------- the tools' --help

class ToolHelp:
    def __init__(self, name, text):
        self.name = name
        self.text = text
        self.flags = set(FLAG.findall(text)) | {"--help"}
        self.takes_value = set()
        for m in re.finditer(r"(--[A-Za-z0-9][A-Za-z0-9_-]*) ([^\s\[\]]+)", text):
            value = m.group(2).rstrip(".]")
            if re.match(r"^[A-Z][A-Za-z0-9_:,=.|]*$", value) or "|" in value:
                self.takes_value.add(m.group(1))
        # Sub-commands: usage lines "  avsm-sweep NAME ..." and their deeper-indented lines.
        self.subcommands = {}
        current = None
        for line in text.split("\n"):
            m = re.match(r"^(\s*)%s\s+([a-z][a-z0-9-]*)\b" % re.escape(name), line)
            if m:
                current = m.group(2)
                indent = len(m.group(1))
                self.subcommands.setdefault(current, set()).update(FLAG.findall(line))
            elif current and line.strip() and len(line) - len(line.lstrip()) > indent:
                self.subcommands[current].update(FLAG.findall(line))
            else:
                current = None

    def allowed(self, subcommand):
        if subcommand and subcommand in self.subcommands:
            return self.subcommands[subcommand] | {"--help"}
        return self.flags


def read_help(name, exe):
    env = dict(os.environ)
    env.setdefault("XDG_RUNTIME_DIR", "/tmp")
    try:
        run = subprocess.run([exe, "--help"], capture_output=True, text=True, timeout=120, env=env)
    except (OSError, subprocess.TimeoutExpired) as e:
        sys.exit("check_docs.py: cannot run '%s --help': %s" % (exe, e))
    if run.returncode != 0:
        sys.exit("check_docs.py: '%s --help' exited with %d:\n%s" % (exe, run.returncode, run.stderr))
    return ToolHelp(name, run.stdout)


# ---------------------------------------------------------------- flags on command lines

def tool_of_word(word):
    word = word.strip("\"'")
    if word == "tools/capture.sh" or word.endswith("/tools/capture.sh"):
        return "avsm-capture"
    base = word.rsplit("/", 1)[-1]
    return base if base in TOOLS else None


def command_uses(words):
    """[(tool, sub-command, flag, the flag's word index)] of one command line's words."""
    uses = []
    i, n = 0, len(words)
    while i < n:
        # One command: skip assignments and wrappers, then the command word.
        while i < n and (re.match(r"^[A-Za-z_][A-Za-z0-9_]*=", words[i]) or words[i] == "$"):
            i += 1
        while i < n and words[i] in WRAPPERS:
            wrapper = words[i]
            i += 1
            while i < n and (words[i].startswith("-") or re.match(r"^[A-Za-z_][A-Za-z0-9_]*=", words[i])):
                i += 1
            if wrapper == "timeout" and i < n and re.match(r"^[0-9.]+[smhd]?$", words[i]):
                i += 1
        if i >= n:
            break
        tool = tool_of_word(words[i])
        i += 1
        subcommand = None
        if tool == "avsm-sweep" and i < n and re.match(r"^[a-z][a-z0-9-]*$", words[i]):
            subcommand = words[i]
            uses.append((tool, subcommand, None, i))
            i += 1
        while i < n and words[i] not in SEPARATORS:
            if tool:
                for flag in FLAG.findall(words[i]):
                    uses.append((tool, subcommand, flag, i))
            i += 1
        i += 1  # the separator
    return uses


def split_words(text):
    # Separators glued to a word ("a;", "x&&y") become words of their own.
    text = re.sub(r"(\s|^)(\|\||&&|\||;)(?=\s|$)", r"\1 \2 ", text)
    text = re.sub(r";(\s|$)", r" ; \1", text)
    return text.split()


class FlagChecker:
    def __init__(self, helps, problems, notes):
        self.helps, self.problems, self.notes = helps, problems, notes
        self.skipped = set()
        self.checked = 0
        self.listing = None  # a list to append (file, line, tool, flag) to: --list

    def check(self, rel, line, tool, subcommand, flag, context):
        help_ = self.helps.get(tool)
        if help_ is None:
            if tool not in self.skipped:
                self.skipped.add(tool)
                self.notes.append("note: %s flags not checked: no %s executable given" % (tool, tool))
            return
        if flag is None:  # the sub-command word itself
            if subcommand not in help_.subcommands:
                self.problems.append("%s:%d: %s has no sub-command '%s' (its --help lists: %s)  [%s]" %
                                     (rel, line, tool, subcommand, ", ".join(sorted(help_.subcommands)), context))
            return
        self.checked += 1
        if self.listing is not None:
            self.listing.append("%s:%d: %s%s %s" % (rel, line, tool, " " + subcommand if subcommand else "", flag))
        if flag not in help_.allowed(subcommand):
            where = "%s %s" % (tool, subcommand) if subcommand in help_.subcommands else tool
            self.problems.append("%s:%d: unknown flag %s for %s: not in '%s --help'  [%s]" %
                                 (rel, line, flag, where, tool, context.strip()))

    def check_words(self, rel, line, words, context):
        skip = set()
        uses = command_uses(words)
        for tool, subcommand, flag, index in uses:
            if index in skip:
                continue
            self.check(rel, line, tool, subcommand, flag, context)
            help_ = self.helps.get(tool)
            if flag and help_ and words[index] == flag and flag in help_.takes_value:
                skip.add(index + 1)  # its value, even when it looks like a flag


def strip_comment(line):
    return re.sub(r"(^|\s)#.*$", "", line)


def check_flags(page, checker):
    # a. Shell code blocks, line by line; continuation lines keep the command.
    for language, lines in page.blocks:
        if language not in SHELL_LANGUAGES:
            continue
        command_words, command_line, continued = [], 0, False
        pending = []
        for number, raw in lines:
            line = strip_comment(raw)
            line = re.sub(r"^\s*\$\s+", "", line)
            starts_with_flag = re.match(r"^\s*--", line) is not None
            if not (continued or (starts_with_flag and command_words)):
                if command_words:
                    pending.append((command_line, command_words))
                command_words, command_line = [], number
            words = split_words(line.rstrip().rstrip("\\"))
            command_words = command_words + [(w, number) for w in words]
            continued = raw.rstrip().endswith("\\")
        if command_words:
            pending.append((command_line, command_words))
        for first_line, words in pending:
            plain = [w for w, _ in words]
            skip = set()
            for tool, subcommand, flag, index in command_uses(plain):
                if index in skip:
                    continue
                checker.check(page.rel, words[index][1], tool, subcommand, flag, " ".join(plain))
                help_ = checker.helps.get(tool)
                if flag and help_ and plain[index] == flag and flag in help_.takes_value:
                    skip.add(index + 1)

    # b. Inline code spans: a command when the span starts with a word, prose when with --.
    rules = PROSE_RULES.get(page.rel, {})
    headings = page.headings()

    def prose_tool(line):
        stack = []
        for number, level, text in headings:
            if number > line:
                break
            stack = [h for h in stack if h[0] < level] + [(level, text)]
        for _, text in reversed(stack):
            key = re.sub(r"`", "", text).strip()
            if key in rules:
                return rules[key]
        return rules.get(None)

    def check_prose_flag(line, flag, context):
        rule = prose_tool(line)
        if rule:
            tool, _, subcommand = rule.partition(" ")
            checker.check(page.rel, line, tool, subcommand or None, flag, context)

    for start, _, content in page.code_spans():
        line = page.line_of(start)
        words = split_words(content)
        if not words:
            continue
        if words[0].startswith("--"):
            for flag in FLAG.findall(content):
                check_prose_flag(line, flag, "`%s`" % content)
        else:
            checker.check_words(page.rel, line, words, "`%s`" % content)
    # Plain text outside code: prose flags.
    text = page.prose_without_code()
    text = re.sub(r"\]\([^)]*\)", "]()", text)  # not inside link targets
    for m in FLAG.finditer(text):
        line = page.line_of(m.start())
        check_prose_flag(line, m.group(0), page.lines[line - 1].strip())


# ---------------------------------------------------------------- main

def markdown_pages(repo):
    pages = [os.path.join(repo, "README.md")]
    docs = os.path.join(repo, "docs")
    for root, dirs, files in os.walk(docs):
        dirs.sort()
        pages += [os.path.join(root, f) for f in sorted(files) if f.endswith(".md")]
    return [p for p in pages if os.path.isfile(p)]


def check(repo, helps, out=sys.stdout, listing=None):
    problems, notes = [], []
    checker = FlagChecker(helps, problems, notes)
    checker.listing = listing
    cache = {}
    counts = {"links": 0}
    pages = markdown_pages(repo)
    for path in pages:
        page = Page(path, os.path.relpath(path, repo).replace(os.sep, "/"))
        cache[path] = page
        check_links(page, repo, problems, cache, counts)
        check_flags(page, checker)
    for entry in listing or []:
        print(entry, file=out)
    for note in notes:
        print(note, file=out)
    for problem in problems:
        print(problem, file=out)
    print("check_docs.py: %d pages, %d relative links, %d tool flags checked against --help (%s); %d problem%s" %
          (len(pages), counts["links"], checker.checked, ", ".join(sorted(helps)) or "no tools", len(problems),
           "" if len(problems) == 1 else "s"), file=out)
    return problems


def self_test(helps):
    """The checker must fail on planted errors, naming file, line and the link or flag."""
    import io
    with tempfile.TemporaryDirectory() as repo:
        os.makedirs(os.path.join(repo, "docs"))
        with open(os.path.join(repo, "README.md"), "w") as f:
            f.write("# Top\n\nSee [the page](docs/page.md#good-section) and [gone](docs/missing.md).\n")
        with open(os.path.join(repo, "docs", "page.md"), "w") as f:
            f.write("# Page\n\n## Good section\n\n[bad anchor](#no-such-section), [up](../README.md)\n\n"
                    "```sh\nbuild/tools/avsm-capture --width 96 --no-such-capture-flag\n"
                    "avsm-sweep run m.json --out d --jobs 2 --partition gpu\n"
                    "tools/capture.sh --frames 1 && cmake --not-ours\n```\n")
        out = io.StringIO()
        problems = check(repo, helps, out)
    print(out.getvalue(), end="")
    expected = [
        r"^README\.md:3: broken link 'docs/missing\.md'",
        r"^docs/page\.md:5: broken link '#no-such-section'",
        r"^docs/page\.md:8: unknown flag --no-such-capture-flag for avsm-capture",
    ]
    if "avsm-sweep" in helps:
        expected.append(r"^docs/page\.md:9: unknown flag --partition for avsm-sweep run")
    missing = [e for e in expected if not any(re.search(e, p) for p in problems)]
    extra = [p for p in problems if not any(re.search(e, p) for e in expected)]
    if missing or extra:
        print("self-test FAILED: expected %s, unexpected %s" % (missing, extra))
        return 1
    print("self-test passed: the %d planted errors were reported, nothing else" % len(expected))
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repo", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    for tool in TOOLS:
        parser.add_argument("--" + tool.split("-")[1], metavar="EXE", help="the %s executable" % tool)
    parser.add_argument("--self-test", action="store_true", help="check planted errors are caught")
    parser.add_argument("--list", action="store_true", help="print every flag checked and the tool it went to")
    args = parser.parse_args()
    helps = {}
    for tool in TOOLS:
        exe = getattr(args, tool.split("-")[1])
        if exe:
            helps[tool] = read_help(tool, exe)
    if args.self_test:
        return self_test(helps)
    return 1 if check(os.path.abspath(args.repo), helps, listing=[] if args.list else None) else 0


if __name__ == "__main__":
    sys.exit(main())
