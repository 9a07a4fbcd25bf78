"""The IR as text that reads back: :func:`print_ir` writes it, :func:`parse_ir` reads it (docs/ir.md).

One command per line, ``Name @source:start-end fN field=value ...``; the frames are
written once each, ``frame fN = Frame(...)``, before the first command that uses them.
Values are written so that they read back equal: floats by ``repr`` (shortest exact
form), strings JSON-quoted, enums ``Type.MEMBER``, tuples ``(a, b)``, records
``Type(field=value, ...)``.  Fields at their default are left out.  ``;`` starts a
comment (the printer puts the source position and line there).

The reader checks every value against the field's declared type and reports what is
wrong at its line and column: E0194 (the text is not IR text) and E0195 (a name, field
or value the IR does not have); a bad line is skipped.
"""

from __future__ import annotations

import dataclasses
import enum
import json
import re
import types
import typing
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field

from cncc import diagnostics as dg
from cncc.ir import commands as c
from cncc.ir import css, frame, modes
from cncc.source import SourceMap, Span

FORMAT_HEADER = "; cncc IR text 1"

_COMMANDS: tuple[type, ...] = (
    c.Rapid, c.Linear, c.Arc, c.Dwell, c.Spindle, c.SpindleSpeed, c.FeedRate, c.Coolant, c.SelectTool,
    c.ToolChange, c.Stop, c.Comment, c.Message, c.Aux, c.Wait, c.Cycle, *modes.MODE_TYPES,
)
_RECORDS: tuple[type, ...] = (
    *_COMMANDS, c.Motion, c.Origin, css.Css, frame.Frame, frame.Scaling, frame.Mirror, frame.Rotation, frame.Polar,
)
_ENUMS: tuple[type[enum.Enum], ...] = (
    c.PathMode, c.SpindleState, c.CoolantState, c.StopKind, c.CycleKind, c.OriginKind, frame.Units, frame.Plane,
    frame.CompSide, modes.FeedMode, modes.ToolData,
)


@dataclass(slots=True)
class Vocabulary:
    """The record and enum types IR text may name (a dialect layer adds its own with :meth:`add`)."""

    records: dict[str, type] = field(default_factory=lambda: {t.__name__: t for t in _RECORDS})
    enums: dict[str, type[enum.Enum]] = field(default_factory=lambda: {t.__name__: t for t in _ENUMS})

    def add(self, t: type) -> None:
        if self.enums.get(t.__name__, t) is not t or self.records.get(t.__name__, t) is not t:
            raise ValueError(f"two IR types named {t.__name__}")
        if issubclass(t, enum.Enum):
            self.enums[t.__name__] = t
        else:
            self.records[t.__name__] = t


DEFAULT_VOCABULARY = Vocabulary()


# ---- writing ---------------------------------------------------------------------------------------
def format_value(v: object) -> str:
    """One value as IR text."""
    if v is None:
        return "none"
    if v is True or v is False:
        return "true" if v else "false"
    if isinstance(v, enum.Enum):
        return f"{type(v).__name__}.{v.name}"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, tuple):
        inner = ", ".join(format_value(x) for x in v)
        return f"({inner},)" if len(v) == 1 else f"({inner})"
    if dataclasses.is_dataclass(v) and not isinstance(v, type):
        return f"{type(v).__name__}({_fields_text(v, ', ')})"
    raise TypeError(f"no IR text for {type(v).__name__}")


_DEFAULT_TEXT: dict[tuple[type, str], str | None] = {}


def _is_default(owner: type, f: dataclasses.Field[object], v: object) -> bool:
    """``v`` is the field's default, to the sign of a zero (compared as text, which is exact)."""
    key = (owner, f.name)
    d = _DEFAULT_TEXT.get(key, "")
    if d == "":
        d = _DEFAULT_TEXT[key] = None if f.default is dataclasses.MISSING else format_value(f.default)
    return d is not None and format_value(v) == d


def _fields_text(v: object, sep: str, skip: tuple[str, ...] = ()) -> str:
    parts = []
    for f in dataclasses.fields(v):  # type: ignore[arg-type]
        if not f.init or f.name in skip:
            continue
        val = getattr(v, f.name)
        if not _is_default(type(v), f, val):
            parts.append(f"{f.name}={format_value(val)}")
    return sep.join(parts)


def _span_text(s: Span) -> str:
    return f"@{s.source_id}:{s.start}-{s.end}"


def print_ir(cmds: Iterable[c.Command], sources: SourceMap | None = None) -> Iterator[str]:
    """The IR text of ``cmds``, line by line (with newlines); ``sources`` adds each command's source line."""
    yield FORMAT_HEADER + "\n"
    by_id: dict[int, tuple[frame.Frame, str]] = {}
    by_value: dict[frame.Frame, str] = {}
    for cmd in cmds:
        f = cmd.frame
        got = by_id.get(id(f))
        if got is None or got[0] is not f:
            label = by_value.get(f)
            if label is None:
                label = by_value[f] = f"f{len(by_value)}"
                yield f"frame {label} = {format_value(f)}\n"
            got = by_id[id(f)] = (f, label)
        fields = _fields_text(cmd, " ", ("span", "frame"))
        line = f"{type(cmd).__name__} {_span_text(cmd.span)} {got[1]}" + (f" {fields}" if fields else "")
        yield line + _source_note(cmd.span, sources) + "\n"


def _source_note(span: Span, sources: SourceMap | None) -> str:
    if sources is None:
        return ""
    src = sources.get(span.source_id)
    if src is None:
        return ""
    text = src.line_text(src.position(span.start).line).strip()
    return f"  ; {sources.describe(span)}: {text}"


def ir_text(cmds: Iterable[c.Command], sources: SourceMap | None = None) -> str:
    return "".join(print_ir(cmds, sources))


# ---- reading ---------------------------------------------------------------------------------------
_TOKEN = re.compile(r"""
    (?P<ws>[ \t\r]+)
  | (?P<comment>;.*)
  | (?P<str>"(?:[^"\\]|\\.)*")
  | (?P<span>@-?\d+:\d+-\d+)
  | (?P<float>[-+]?(?:\d+\.\d*(?:[eE][-+]?\d+)?|\d+[eE][-+]?\d+|inf\b|nan\b))
  | (?P<int>[-+]?\d+\b)
  | (?P<name>[A-Za-z_]\w*(?:\.[A-Za-z_]\w*)?)
  | (?P<punct>[()=,])
""", re.VERBOSE)


@dataclass(frozen=True, slots=True)
class _Tok:
    kind: str
    text: str
    start: int  # offset in the whole text
    end: int


class IrTextError(Exception):
    def __init__(self, code: str, tok: _Tok | tuple[int, int], message: str) -> None:
        super().__init__(message)
        self.code = code
        self.start, self.end = (tok.start, tok.end) if isinstance(tok, _Tok) else tok
        self.message = message


def _tokens(line: str, base: int) -> list[_Tok]:
    out: list[_Tok] = []
    pos = 0
    while pos < len(line):
        m = _TOKEN.match(line, pos)
        if m is None:  # the parser says what it expected here
            out.append(_Tok("bad", line[pos], base + pos, base + pos + 1))
            pos += 1
            continue
        kind = m.lastgroup or ""
        if kind == "comment":
            break
        if kind != "ws":
            out.append(_Tok(kind, m.group(), base + m.start(), base + m.end()))
        pos = m.end()
    return out


class _Line:
    def __init__(self, toks: list[_Tok], end: int) -> None:
        self.toks, self.i, self.end = toks, 0, end

    def peek(self) -> _Tok | None:
        return self.toks[self.i] if self.i < len(self.toks) else None

    def take(self, what: str) -> _Tok:
        t = self.peek()
        if t is None:
            raise IrTextError(dg.IR_TEXT_SYNTAX, (self.end, self.end), f"the line ends where {what} is expected")
        self.i += 1
        return t

    def expect(self, text: str) -> _Tok:
        t = self.take(f"'{text}'")
        if t.text != text:
            raise IrTextError(dg.IR_TEXT_SYNTAX, t, f"'{text}' expected, not {t.text!r}")
        return t


_HINTS: dict[type, dict[str, object]] = {}


def _hints(t: type) -> dict[str, object]:
    got = _HINTS.get(t)
    if got is None:
        got = _HINTS[t] = typing.get_type_hints(t)
    return got


def _type_ok(v: object, hint: object) -> bool:
    """Does ``v`` (as read) fit the declared type ``hint``?"""
    origin = typing.get_origin(hint)
    args = typing.get_args(hint)
    if origin in (types.UnionType, typing.Union):
        return any(_type_ok(v, a) for a in args)
    if origin is tuple:
        if not isinstance(v, tuple):
            return False
        if len(args) == 2 and args[1] is Ellipsis:
            return all(_type_ok(x, args[0]) for x in v)
        return len(v) == len(args) and all(_type_ok(x, a) for x, a in zip(v, args, strict=True))
    if hint is type(None):
        return v is None
    if hint is float:
        return isinstance(v, int | float) and not isinstance(v, bool)
    if hint is int:
        return isinstance(v, int) and not isinstance(v, bool)
    if isinstance(hint, type):
        return isinstance(v, hint)
    return True  # a type the reader does not check (none in the IR today)


class _Reader:
    def __init__(self, vocab: Vocabulary) -> None:
        self.vocab = vocab
        self.frames: dict[str, frame.Frame] = {}

    def value(self, ln: _Line) -> object:
        t = ln.take("a value")
        match t.kind:
            case "float":
                return float(t.text)
            case "int":
                return int(t.text)
            case "str":
                try:
                    return str(json.loads(t.text))
                except ValueError:
                    raise IrTextError(dg.IR_TEXT_SYNTAX, t, f"a malformed string {t.text}") from None
            case "punct" if t.text == "(":
                return self.tuple_rest(ln)
            case "name":
                return self.named(ln, t)
        raise IrTextError(dg.IR_TEXT_SYNTAX, t, f"a value expected, not {t.text!r}")

    def tuple_rest(self, ln: _Line) -> tuple[object, ...]:
        items: list[object] = []
        while True:
            t = ln.peek()
            if t is not None and t.text == ")":
                ln.i += 1
                return tuple(items)
            items.append(self.value(ln))
            t = ln.take("',' or ')'")
            if t.text == ")":
                return tuple(items)
            if t.text != ",":
                raise IrTextError(dg.IR_TEXT_SYNTAX, t, f"',' or ')' expected, not {t.text!r}")

    def named(self, ln: _Line, t: _Tok) -> object:
        consts: dict[str, object] = {"none": None, "true": True, "false": False}
        if t.text in consts:
            return consts[t.text]
        if "." in t.text:
            type_name, member = t.text.split(".", 1)
            et = self.vocab.enums.get(type_name) or _dialect_cycle_kinds().get(type_name)
            if et is None:
                raise IrTextError(dg.IR_TEXT_NAME, t, f"no IR enum named {type_name}")
            if member not in et.__members__:
                raise IrTextError(dg.IR_TEXT_NAME, t, f"{type_name} has no member {member}")
            return et[member]
        rt = self.vocab.records.get(t.text)
        if rt is None or _is_command_type(rt):
            raise IrTextError(dg.IR_TEXT_NAME, t, f"no IR value type named {t.text}")
        ln.expect("(")
        kwargs: dict[str, tuple[_Tok, object]] = {}
        while True:
            nt = ln.peek()
            if nt is not None and nt.text == ")":
                ln.i += 1
                break
            self.field(ln, kwargs)
            sep = ln.take("',' or ')'")
            if sep.text == ")":
                break
            if sep.text != ",":
                raise IrTextError(dg.IR_TEXT_SYNTAX, sep, f"',' or ')' expected, not {sep.text!r}")
        return self.build(rt, kwargs, t)

    def field(self, ln: _Line, kwargs: dict[str, tuple[_Tok, object]]) -> None:
        nt = ln.take("a field name")
        if nt.kind != "name" or "." in nt.text:
            raise IrTextError(dg.IR_TEXT_SYNTAX, nt, f"a field name expected, not {nt.text!r}")
        if nt.text in kwargs:
            raise IrTextError(dg.IR_TEXT_NAME, nt, f"the field {nt.text} is given twice")
        ln.expect("=")
        kwargs[nt.text] = (nt, self.value(ln))

    def build(self, rt: type, kwargs: dict[str, tuple[_Tok, object]], at: _Tok,
              fixed: dict[str, object] | None = None) -> object:
        hints = _hints(rt)
        init = {f.name: f for f in dataclasses.fields(rt) if f.init}
        for name, (nt, v) in kwargs.items():
            if name not in init or (fixed and name in fixed):
                raise IrTextError(dg.IR_TEXT_NAME, nt, f"{rt.__name__} has no field {name}")
            if not _type_ok(v, hints[name]):
                raise IrTextError(dg.IR_TEXT_NAME, nt, f"{rt.__name__}.{name} takes {_hint_text(hints[name])}, "
                                                       f"not {format_value(v)}")
        args = {**(fixed or {}), **{k: v for k, (_, v) in kwargs.items()}}
        missing = [n for n, f in init.items() if n not in args and f.default is dataclasses.MISSING
                   and f.default_factory is dataclasses.MISSING]
        if missing:
            raise IrTextError(dg.IR_TEXT_NAME, at, f"{rt.__name__} needs {', '.join(missing)}")
        return rt(**args)

    def line(self, ln: _Line) -> c.Command | None:
        head = ln.take("a command")
        if head.kind != "name":
            raise IrTextError(dg.IR_TEXT_SYNTAX, head, f"a command name expected, not {head.text!r}")
        if head.text == "frame":
            self.frame_def(ln)
            return None
        rt = self.vocab.records.get(head.text)
        if rt is None or not _is_command_type(rt):
            raise IrTextError(dg.IR_TEXT_NAME, head, f"no IR command named {head.text}")
        st = ln.take("a span (@source:start-end)")
        if st.kind != "span":
            raise IrTextError(dg.IR_TEXT_SYNTAX, st, f"a span (@source:start-end) expected, not {st.text!r}")
        sid, rng = st.text[1:].split(":")
        a, b = rng.split("-")
        ft = ln.take("a frame label")
        fr = self.frames.get(ft.text)
        if fr is None:
            raise IrTextError(dg.IR_TEXT_NAME, ft, f"no frame {ft.text} defined above")
        kwargs: dict[str, tuple[_Tok, object]] = {}
        while ln.peek() is not None:
            self.field(ln, kwargs)
        return typing.cast(c.Command, self.build(rt, kwargs, head, {"span": Span(int(sid), int(a), int(b)),
                                                                     "frame": fr}))

    def frame_def(self, ln: _Line) -> None:
        label = ln.take("a frame label")
        if label.kind != "name" or not re.fullmatch(r"f\d+", label.text):
            raise IrTextError(dg.IR_TEXT_SYNTAX, label, f"a frame label (f0, f1 ...) expected, not {label.text!r}")
        ln.expect("=")
        at = ln.peek()
        v = self.value(ln)
        if not isinstance(v, frame.Frame):
            raise IrTextError(dg.IR_TEXT_NAME, at or label, "a frame is defined as Frame(...)")
        self.frames[label.text] = v
        extra = ln.peek()
        if extra is not None:
            raise IrTextError(dg.IR_TEXT_SYNTAX, extra, f"nothing expected after the frame, not {extra.text!r}")


def _dialect_cycle_kinds() -> dict[str, type[enum.Enum]]:
    """The cycle kind enums of the dialect layers loaded (``cncc/dialects/series8_cycles.py``)."""
    return {t.__name__: t for t in c.CycleKindBase.__subclasses__()}


def _is_command_type(t: type) -> bool:
    """A command type a dialect layer registered: a record with a span and a frame."""
    names = {f.name for f in dataclasses.fields(t)} if dataclasses.is_dataclass(t) else set()
    return {"span", "frame"} <= names


def parse_ir(text: str, sink: dg.DiagnosticSink | None = None, source_id: int = 0,
             vocabulary: Vocabulary = DEFAULT_VOCABULARY) -> list[c.Command]:
    """The commands of IR text.  Errors go to ``sink`` (spans in ``source_id``, the text's id) and skip the
    line; without a sink the first error raises :class:`IrTextError`."""
    reader = _Reader(vocabulary)
    out: list[c.Command] = []
    base = 0
    for raw in text.splitlines(keepends=True):
        line = raw.rstrip("\n")
        try:
            toks = _tokens(line, base)
            if toks:
                cmd = reader.line(_Line(toks, base + len(line.rstrip())))
                if cmd is not None:
                    out.append(cmd)
        except IrTextError as e:
            if sink is None:
                raise
            sink.emit(e.code, Span(source_id, e.start, max(e.end, e.start)), e.message)
        base += len(raw)
    return out


def _hint_text(hint: object) -> str:
    if isinstance(hint, type):
        return hint.__name__
    return str(hint).replace("cncc.ir.frame.", "").replace("cncc.ir.commands.", "").replace("cncc.ir.css.", "")
