"""Parser: program text -> syntax :class:`~cncc.frontend.syntax.Block` stream.

The lark grammar (``cncc/grammar/<family>.lark``) defines the language.  Each
physical line is parsed on its own, so an error costs one line and the parse goes
on at the next block.  Lines made only of plain words (``N10 G1 X1.5 Y-2 F300``,
optionally with a trailing comment) take a regular-expression fast path that
builds the same nodes; ``tests/frontend/test_fastpath.py`` checks the two agree.
"""

from __future__ import annotations

import functools
import re
import threading
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from importlib import resources
from typing import Any, ParamSpec, TypeVar, cast

from lark import Lark, Token, Transformer
from lark.exceptions import LarkError, UnexpectedCharacters, UnexpectedEOF, UnexpectedInput

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.frontend import syntax as sx
from cncc.frontend.linuxcnc.builder import LinuxcncBuilder
from cncc.frontend.number_check import refused_numbers
from cncc.frontend.series8.builder import Series8Builder
from cncc.frontend.szgh_builder import SzghBuilder
from cncc.source import SourceFile, Span

_P = ParamSpec("_P")
_T = TypeVar("_T")
MAX_LINE_CHARS = 100_000
"""Lines longer than this are rejected (a 10 MB line is not a G-code block)."""


@dataclass(frozen=True, slots=True)
class ParseOptions:
    strict: bool = False  # malformed numbers are errors rather than warnings


def abbreviations(dialect: Dialect) -> tuple[tuple[str, str], ...]:
    """(word, abbreviation) pairs of the dialect's macro words (``WH`` for WHILE, ``GO`` for
    GOTO, ``AT`` for ATAN ...): ``Dialect.lexicon.abbreviations``."""
    return dialect.lexicon.abbreviations


def _with_abbreviations(line: str, pairs: tuple[tuple[str, str], ...]) -> str:
    """A terminal line ``NAME.p: /A|B/i`` with each word's abbreviation as one more alternative."""
    if not re.match(r"^(%override )?[A-Z_]+(\.\d+)?:\s*/", line):
        return line
    for word, short in pairs:
        line = re.sub(rf"(?<=[/(|]){word}(?=[/)|])", f"{word}|{short}", line)
    return line


_IMPORT_ALL = re.compile(r"^%import (\w+) \(@all\)[ \t]*$", re.MULTILINE)
_DEFINED = re.compile(r"^\??([A-Za-z_]\w*)(?:\.\d+)?[ \t]*:", re.MULTILINE)
_ALIAS = re.compile(r"->[ \t]*(\w+)")


def grammar_text(family: str, comments: tuple[str, ...], block_end: str,
                 abbreviated: tuple[tuple[str, str], ...] = (), functions: tuple[str, ...] = ()) -> str:
    """The grammar of ``family`` for one dialect (:func:`family_text`), with each
    ``%import NAME (@all)`` naming every rule and terminal that ``NAME.lark`` defines for
    the same dialect (so a grammar extends the base one with ``%override``/``%extend``;
    :func:`grammar_loader` gives lark that text)."""
    text = family_text(family, comments, block_end, abbreviated, functions)

    def every_name(m: re.Match[str]) -> str:
        base = family_text(m.group(1), comments, block_end, abbreviated, functions)
        names = list(dict.fromkeys(_DEFINED.findall(base) + _ALIAS.findall(base)))  # aliases are mangled too
        return f"%import {m.group(1)} ({', '.join(names)})"

    return _IMPORT_ALL.sub(every_name, text)


def grammar_loader(comments: tuple[str, ...], block_end: str, abbreviated: tuple[tuple[str, str], ...] = (),
                   functions: tuple[str, ...] = ()) -> Callable[[object, str], tuple[str, str]]:
    """A lark import loader: ``%import fanuc`` reads ``cncc/grammar/fanuc.lark`` as :func:`family_text`
    gives it for the dialect."""
    def load(_base: object, grammar_path: str) -> tuple[str, str]:
        family = grammar_path.removesuffix(".lark")
        if not resources.files("cncc.grammar").joinpath(f"{family}.lark").is_file():
            raise OSError(grammar_path)
        return f"cncc/grammar/{grammar_path}", family_text(family, comments, block_end, abbreviated, functions)

    return load


def family_text(family: str, comments: tuple[str, ...], block_end: str,
                abbreviated: tuple[tuple[str, str], ...] = (), functions: tuple[str, ...] = ()) -> str:
    """The text of ``cncc/grammar/<family>.lark`` with the dialect's comment and block-end forms,
    its function names in place of ``@functions`` (``Dialect.lexicon``), and the abbreviations of
    its macro words (:func:`abbreviations`)."""
    text = resources.files("cncc.grammar").joinpath(f"{family}.lark").read_text(encoding="utf-8")
    names = sorted(functions, key=lambda f: (-len(f), f))
    text = text.replace("@functions", "|".join(names) if names else "(?!)")
    enabled = set(comments)
    terminals = {"paren": ["PAREN_COMMENT", "UNCLOSED_PAREN"], "slash": ["SLASH_COMMENT"], "semi": ["SEMI_COMMENT"]}
    end_tag = "semi" if block_end == ";" else "none"
    out = []
    for line in text.splitlines():
        tag = re.search(r"// @(comment|block_end):(\w+)\s*$", line)
        if tag is not None:
            if tag.group(1) == "comment" and tag.group(2) not in enabled:
                continue
            if tag.group(1) == "block_end" and tag.group(2) != end_tag:
                continue
        if line.rstrip().endswith("// @comment-rule"):
            names = [t for kind in ("paren", "slash", "semi") if kind in enabled for t in terminals[kind]]
            line = "comment: " + " | ".join(names) if names else ""
        if abbreviated:
            line = _with_abbreviations(line, abbreviated)
        out.append(line)
    return "\n".join(out) + "\n"


class _Builder(SzghBuilder, LinuxcncBuilder, Series8Builder, Transformer[Token, Any]):
    """Builds syntax nodes with absolute offsets (``base`` is the line's offset).

    The builder is embedded in its lark parser and holds per-line state (``base``,
    ``bad_numbers``), so :func:`_lark` caches one pair per thread.
    """

    def __init__(self, full_words: dict[str, str] | None = None) -> None:
        super().__init__()
        self.base = 0
        self.bad_numbers: list[tuple[int, int, str]] = []
        self.full_words = full_words or {}  # abbreviation -> macro word ("WH" -> "WHILE")

    # -- helpers
    def _num(self, tok: Token) -> sx.Num:
        text = str(tok)
        start = self.base + (tok.start_pos or 0)
        end = start + len(text)
        if text.count(".") > 1:
            self.bad_numbers.append((start, end, text))
            text = text[:-1]
        return sx.Num(float(text), "." in text, start, end)

    # -- words
    def number(self, items: list[Any]) -> sx.Num:
        return self._num(items[0])

    def signed_number(self, items: list[Any]) -> sx.Num:
        sign, tok = items
        num = self._num(tok)
        value = -num.value if sign == "-" else num.value
        return sx.Num(value, num.point, self.base + (sign.start_pos or 0), num.end)

    def var_value(self, items: list[Any]) -> sx.Expr:
        return self._signed_expr(items)

    def expr_value(self, items: list[Any]) -> sx.Expr:
        return self._signed_expr(items)

    def _signed_expr(self, items: list[Any]) -> sx.Expr:
        if len(items) == 2:
            sign, expr = items
            if sign == "-":
                return sx.Neg(expr, self.base + (sign.start_pos or 0), _end(expr))
            return cast(sx.Expr, expr)
        return cast(sx.Expr, items[0])

    def word(self, items: list[Any]) -> sx.Word:
        letter_tok, value = items
        start = self.base + (letter_tok.start_pos or 0)
        if isinstance(value, sx.Num):
            return sx.Word(letter_tok.upper(), value.value, value.point, start, value.end)
        return sx.Word(letter_tok.upper(), 0.0, False, start, _end(value), value)

    def comment(self, items: list[Any]) -> sx.CommentItem:
        tok = items[0]
        text = str(tok)
        start = self.base + (tok.start_pos or 0)
        return sx.CommentItem(text, start, start + len(text))

    # -- expressions
    def neg(self, items: list[Any]) -> sx.Expr:
        sign, operand = items
        if sign == "+":
            return operand  # type: ignore[no-any-return]
        return sx.Neg(operand, self.base + (sign.start_pos or 0), _end(operand))

    def _binary(self, items: list[Any]) -> sx.Expr:
        expr = items[0]
        for i in range(1, len(items), 2):
            op, right = items[i], items[i + 1]
            name = str(op).upper()
            expr = sx.BinOp(self.full_words.get(name, name), expr, right, _start(expr), _end(right))
        return expr  # type: ignore[no-any-return]

    compare = sum = product = _binary

    def call(self, items: list[Any]) -> sx.Call:
        func = items[0]
        args = tuple(items[1:])
        start = self.base + (func.start_pos or 0)
        name = str(func).upper()
        return sx.Call(self.full_words.get(name, name), args, start, _end(args[-1]) + 1)

    def var_number(self, items: list[Any]) -> sx.Var:
        num = self._num(items[0])
        return sx.Var(num, num.start - 1, num.end)

    def var_indirect(self, items: list[Any]) -> sx.Var:
        expr = items[0]
        return sx.Var(expr, _start(expr) - 2, _end(expr) + 1)

    # -- statements
    def assignment(self, items: list[Any]) -> sx.Assign:
        target, expr = items
        return sx.Assign(target, expr, target.start, _end(expr))

    def goto_stmt(self, items: list[Any]) -> sx.Goto:
        kw, target = items
        return sx.Goto(target, self.base + (kw.start_pos or 0), _end(target))

    def then_clause(self, items: list[Any]) -> Any:
        rest = items[1:]
        if len(rest) == 1 and isinstance(rest[0], sx.Assign):
            return rest[0]
        return tuple(rest)

    def if_stmt(self, items: list[Any]) -> sx.If:
        kw, cond, then = items
        end = then.end if not isinstance(then, tuple) else then[-1].end
        return sx.If(cond, then, self.base + (kw.start_pos or 0), end)

    def while_stmt(self, items: list[Any]) -> sx.While:
        kw, cond, _do, num = items
        n = self._num(num)
        return sx.While(cond, int(n.value), self.base + (kw.start_pos or 0), n.end)

    def end_stmt(self, items: list[Any]) -> sx.EndLoop:
        kw, num = items
        n = self._num(num)
        return sx.EndLoop(int(n.value), self.base + (kw.start_pos or 0), n.end)

    # -- blocks
    def block(self, items: list[Any]) -> tuple[Any, ...]:
        return tuple(items)

    def start(self, items: list[Any]) -> list[Any]:
        return [it for it in items if not (isinstance(it, Token) and it.type == "BLOCK_END")]


def _start(node: Any) -> int:
    return int(node.start)


def _end(node: Any) -> int:
    return int(node.end)


def _per_thread(build: Callable[_P, _T]) -> Callable[_P, _T]:
    """:func:`functools.cache` with one cache per thread.

    The language server parses in several threads at once; a parser shared between
    threads mixed their line offsets (tests/frontend/test_parser_threads.py).  Building a
    parser costs ~35 ms once per thread; a thread-local builder attribute instead cost
    5-15 % on every grammar-path line.
    """
    local = threading.local()

    @functools.wraps(build)
    def cached(*args: _P.args, **kwargs: _P.kwargs) -> _T:
        cache: dict[Any, _T] | None = getattr(local, "cache", None)
        if cache is None:
            cache = local.cache = {}
        key = (args, tuple(sorted(kwargs.items())))
        try:
            return cache[key]
        except KeyError:
            value = cache[key] = build(*args, **kwargs)
            return value

    return cached


@_per_thread
def _lark(family: str, comments: tuple[str, ...], block_end: str,
          abbreviated: tuple[tuple[str, str], ...] = (), functions: tuple[str, ...] = ()) -> tuple[Lark, _Builder]:
    builder = _Builder({short: word for word, short in abbreviated})
    parser = Lark(
        grammar_text(family, comments, block_end, abbreviated, functions),
        import_paths=[grammar_loader(comments, block_end, abbreviated, functions)],
        parser="lalr",
        lexer="contextual",
        transformer=builder,
        maybe_placeholders=False,
    )
    return parser, builder


_FULLWIDTH = str.maketrans({"；": ";", "（": "(", "）": ")", "［": "[", "］": "]", "＃": "#", "＝": "=", "．": ".",
                            "，": ",", "－": "-", "＋": "+", "／": "/", "　": " "})
_WORD_RE = re.compile(r"([A-Za-z])[ \t]*([-+]?)[ \t]*(\d+\.?\d*|\.\d+)")


@functools.cache
def _plain_line_re(comments: tuple[str, ...], block_end: str) -> re.Pattern[str]:
    """A line of plain words, an optional block end and an optional final comment."""
    tail = []
    if "paren" in comments:
        tail.append(r"\([^)]*\)")
    if "slash" in comments:
        tail.append(r"//.*")
    if "semi" in comments:
        tail.append(r";.*")
    end = r"(?:;[ \t]*)?" if block_end == ";" else ""
    comment = f"(?:{'|'.join(tail)})?" if tail else ""
    word = r"[A-Za-z][ \t]*[-+]?[ \t]*(?:\d+\.?\d*|\.\d+)(?![\d.])"
    return re.compile(rf"[ \t]*(?:{word}[ \t]*)*{end}[ \t]*(?P<c>{comment})[ \t]*\r?")


class Parser:
    """Parses the text of one source file for one dialect."""

    def __init__(self, dialect: Dialect, sink: DiagnosticSink, options: ParseOptions | None = None) -> None:
        self.dialect = dialect
        self.sink = sink
        self.options = options or ParseOptions()
        self._comments = dialect.comments
        self._block_end = dialect.block_end
        self._plain = _plain_line_re(self._comments, self._block_end)
        self._family = dialect.grammar
        self._abbreviated = abbreviations(dialect)
        self._functions = dialect.lexicon.functions
        # ISO tape format: ':1000' is the program number O1000 (one character for one)
        self._command = str(dialect.raw.get("system_command_prefix", ""))  # grbl '$H': not G-code
        self._o_marks = tuple(str(m) for m in dialect.raw.get("program_number_marks", []) if len(str(m)) == 1)

    def blocks(self, src: SourceFile) -> Iterator[sx.Block]:
        """Yield the blocks of ``src`` in order."""
        text = src.text
        n = len(text)
        pos = 0
        line_no = 0
        while pos < n:
            nl = text.find("\n", pos)
            end = n if nl < 0 else nl
            line_no += 1
            yield from self.blocks_of_line(src, pos, end, line_no)
            pos = end + 1

    def blocks_of_line(self, src: SourceFile, pos: int, end: int, line_no: int) -> Iterator[sx.Block]:
        """The blocks of the physical line ``src.text[pos:end]`` (line number ``line_no``)."""
        if end - pos > MAX_LINE_CHARS:
            self.sink.emit(dg.LINE_TOO_LONG, Span(src.source_id, pos, pos + 1),
                           f"line is {end - pos} characters long (limit {MAX_LINE_CHARS}); skipped")
            return
        line = src.text[pos:end]
        if not line or line.isspace():
            return
        if not line.isascii():
            line = self._fullwidth(src, line, pos)
        if self._command and line.lstrip().startswith(self._command):
            lead = len(line) - len(line.lstrip())
            text = line.strip()
            yield sx.Block(line_no, pos, pos + len(line.rstrip("\r")), (),
                           (sx.CommentItem(text, pos + lead, pos + lead + len(text)),))
            return
        if self._o_marks and line.lstrip()[:1] in self._o_marks:
            lead = len(line) - len(line.lstrip())
            line = line[:lead] + "O" + line[lead + 1:]
        if self._refuse_numbers(src, line, pos):
            return
        if line == "%" or line == "%\r":  # the tape mark, as every grammar reads it (no grammar built for it)
            yield sx.Block(line_no, pos, pos + 1, (), percent=True)
            return
        m = self._plain.fullmatch(line)
        if m is not None:
            yield self._plain_block(line, pos, line_no, m.start("c"), m.group("c"))
        else:
            yield from self._lark_blocks(src, line, pos, line_no)

    def _refuse_numbers(self, src: SourceFile, line: str, base: int) -> bool:
        """Report exponent notation and overflowing numbers (:mod:`cncc.frontend.number_check`); True: skip."""
        if self.dialect.option("own_number_checks", False):
            return False
        found = False
        for start, end, kind in refused_numbers(line, self._comments, self._block_end, "E" in self.dialect.addresses):
            found = True
            text = line[start:end]
            if kind == "exponent":
                self.sink.emit(dg.EXPONENT_NUMBER, Span(src.source_id, base + start, base + end),
                               f"'{text}' is exponent notation, which controllers do not read; write the digits "
                               "out; block skipped")
            else:
                self.sink.emit(dg.NUMBER_OVERFLOW, Span(src.source_id, base + start, base + end),
                               f"a number of {len(text.lstrip('0'))} integer digits is beyond any controller's "
                               "word format; block skipped")
        return found

    def _fullwidth(self, src: SourceFile, line: str, base: int) -> str:
        """Lenient: full-width punctuation (``；（）``, as in some manuals) read as ASCII.

        The translation maps one character to one, so offsets stay valid.
        """
        norm = line.translate(_FULLWIDTH)
        if norm == line or self.options.strict:
            return line
        col = next(i for i, (a, b) in enumerate(zip(line, norm, strict=True)) if a != b)
        self.sink.emit(dg.FULLWIDTH, Span(src.source_id, base + col, base + col + 1),
                       f"full-width {line[col]!r} read as {norm[col]!r}")
        return norm

    # ---- fast path
    def _plain_block(self, line: str, base: int, line_no: int, cpos: int, comment: str) -> sx.Block:
        body = line[:cpos] if comment else line
        word = sx.Word
        words = []
        for m in _WORD_RE.finditer(body):
            letter, sign, digits = m.groups()
            start, end = m.span()
            words.append(word(letter.upper(), -float(digits) if sign == "-" else float(digits), "." in digits,
                              base + start, base + end))
        comments: tuple[sx.CommentItem, ...] = ()
        if comment:
            comments = (sx.CommentItem(comment, base + cpos, base + cpos + len(comment)),)
        return sx.Block(line_no, base, base + len(line.rstrip("\r")), tuple(words), comments)

    # ---- grammar path
    def _lark_blocks(self, src: SourceFile, line: str, base: int, line_no: int) -> Iterator[sx.Block]:
        parser, builder = _lark(self._family, self._comments, self._block_end, self._abbreviated, self._functions)
        builder.base = base
        bad_numbers: list[tuple[int, int, str]] = []
        builder.bad_numbers = bad_numbers  # read back before the first yield (generators interleave)
        stripped = line.rstrip("\r")
        trailing: sx.CommentItem | None = None
        try:
            parts = cast(list[Any], parser.parse(stripped))
        except UnexpectedInput as exc:
            recovered = self._recover_after_block_end(parser, builder, stripped, base, exc)
            if recovered is None:
                self._syntax_error(src, stripped, base, exc)
                return
            parts, trailing = recovered
        except LarkError as exc:  # pragma: no cover - defensive: grammar bugs
            self.sink.emit(dg.SYNTAX, Span(src.source_id, base, base + 1), f"cannot parse block: {exc}")
            return
        for start, end, text in bad_numbers:
            if self.options.strict or not self.dialect.option("lenient_numbers", True):
                self.sink.emit(dg.BAD_NUMBER, Span(src.source_id, start, end), f"malformed number '{text}'")
            else:
                self.sink.emit(dg.BAD_NUMBER_LENIENT, Span(src.source_id, start, end),
                               f"malformed number '{text}' read as '{text[:-1]}'")
        for k, items in enumerate(parts):
            last = trailing if k == len(parts) - 1 else None
            if items or last is not None:
                yield self._assemble(items, base, stripped, line_no, last)

    def _recover_after_block_end(
        self, parser: Lark, builder: _Builder, line: str, base: int, exc: UnexpectedInput
    ) -> tuple[list[Any], sx.CommentItem] | None:
        """Lenient: free text after the last ';' of a block is taken as a comment."""
        if self._block_end != ";" or self.options.strict:
            return None
        cut = _block_end_before(line, getattr(exc, "pos_in_stream", None) or 0)
        if cut < 0:
            return None
        try:
            parts = cast(list[Any], parser.parse(line[:cut]))
        except LarkError:
            return None
        rest = line[cut + 1:]
        lead = len(rest) - len(rest.lstrip())
        start = base + cut + 1 + lead
        comment = sx.CommentItem(rest.strip(), start, start + len(rest.strip()))
        return parts, comment

    def _syntax_error(self, src: SourceFile, line: str, base: int, exc: UnexpectedInput) -> None:
        col = getattr(exc, "pos_in_stream", None)
        if col is None or col < 0 or isinstance(exc, UnexpectedEOF):
            col = len(line)
        ch = line[col] if col < len(line) else ""
        letter = _bare_letter(line, col)
        if not letter and ch.isalpha():
            rest = line[col + 1:].lstrip(" \t")
            if not rest or not (rest[0].isdigit() or rest[0] in ".#[+-"):
                letter, ch = ch, rest[:1]
                col += 1
        if letter and not (ch.isdigit() or (ch != "" and ch in ".#[")):
            code, what = dg.MISSING_VALUE, f"address {letter.upper()} has no value"
            col = _skip_back(line, col)
        elif isinstance(exc, UnexpectedCharacters) and ch and (not ch.isprintable() or ord(ch) > 126):
            code, what = dg.BAD_CHARACTER, f"character {ch!r} is not part of any G-code dialect"
        elif ch:
            code, what = dg.SYNTAX, f"unexpected {ch!r}"
        else:
            code, what = dg.SYNTAX, "unexpected end of block"
        span = Span(src.source_id, base + col, base + min(col + 1, max(len(line), col + 1)))
        self.sink.emit(code, span, f"{what}; block skipped")

    def _assemble(
        self, items: tuple[Any, ...], base: int, line: str, line_no: int, trailing: sx.CommentItem | None
    ) -> sx.Block:
        words: list[sx.Word] = []
        comments: list[sx.CommentItem] = []
        statements: list[sx.Statement] = []
        block_delete = 0
        percent = False
        for it in items:
            if isinstance(it, sx.Word):
                words.append(it)
            elif isinstance(it, sx.CommentItem):
                comments.append(it)
            elif isinstance(it, Token):
                if it.type == "BLOCK_DELETE":
                    block_delete = int(it[1:]) if len(it) > 1 else 1
                elif it.type == "PERCENT":
                    percent = True
            else:
                statements.append(it)
        if trailing is not None:
            comments.append(trailing)
        return sx.Block(line_no, base, base + len(line), tuple(words), tuple(comments), tuple(statements),
                        block_delete, percent)


def _block_end_before(line: str, pos: int) -> int:
    """Index of the last ';' before ``pos`` that is not inside a comment, or -1."""
    depth = 0
    last = -1
    for i, ch in enumerate(line[:pos]):
        if ch == "(":
            depth += 1
        elif ch == ")":
            depth = max(0, depth - 1)
        elif ch == ";" and depth == 0:
            last = i
    return last


def _skip_back(line: str, col: int) -> int:
    """Column of the last non-blank character before ``col``."""
    j = col - 1
    while j >= 0 and line[j] in " \t":
        j -= 1
    return max(j, 0)


def _bare_letter(line: str, col: int) -> str:
    """The address letter just before ``col`` if it has no value (else "")."""
    j = _skip_back(line, col)
    if j < len(line) and line[j:j + 1].isalpha() and (j == 0 or not line[j - 1].isalpha()):
        return line[j]
    return ""
