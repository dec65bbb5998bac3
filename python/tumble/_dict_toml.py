"""Scenes given as dicts are written as TOML and read by the scene-file reader, so every check is the
file's. Its messages cite lines of that TOML, which the user never saw: this maps them back to the
dict's own path (``bodies[0].shape.size[2]``)."""

from __future__ import annotations

import re


def dumps(table: dict) -> str:
    """The dict as TOML (tomli_w), each array on one line: [1.0, 2.0, 3.0] rather than five lines."""
    import tomli_w
    try:
        text = tomli_w.dumps(table)
    except RecursionError:
        raise ValueError("the scene dict contains itself (a table nested in its own value): a scene is a tree "
                         "of tables, lists and values; give each table once") from None
    return _compact_arrays(text)


def _compact_arrays(text: str) -> str:
    """Arrays of scalars, and arrays of such arrays (a polynomial's terms), put back on one line. Items
    with brackets or braces inside (strings that hold them, inline tables) are left as they are."""
    item = r"(?:[^\[\]\n{}]+|\[[^\[\]\n{}]*\])"
    pattern = re.compile(r"\[\n((?:[ \t]*" + item + r",\n)+)[ \t]*\]")
    while True:
        compacted = pattern.sub(lambda m: "[" + ", ".join(line.strip()[:-1] for line in m.group(1).splitlines()) + "]", text)
        if compacted == text:
            return text
        text = compacted


def _keys(dotted: str) -> list[str]:
    """A dotted TOML key split into its keys, quotes removed (tomli_w quotes keys that are not bare)."""
    return [k[1:-1] if k.startswith('"') else k for k in re.findall(r'"(?:[^"\\]|\\.)*"|[^.\s]+', dotted)]


def _join(prefix: str, key: str) -> str:
    if re.fullmatch(r"[A-Za-z0-9_-]+", key):
        return f"{prefix}.{key}" if prefix else key
    return f'{prefix}["{key}"]'


def _inside(value: str, column: int, path: str) -> str:
    """The path of what `column` (0-based) of a value written on one line points at: into its arrays
    ([i]) and inline tables (.key), from the value's own `path`."""
    stack: list[list] = []  # ["list", index] or ["table", key, where the key starts]
    quote = None
    escaped = False
    for i, c in enumerate(value[:column]):
        if quote:
            if escaped:
                escaped = False
            elif c == "\\" and quote == '"':
                escaped = True
            elif c == quote:
                quote = None
        elif c in "\"'":
            quote = c
        elif c == "[":
            stack.append(["list", 0])
        elif c == "{":
            stack.append(["table", None, i + 1])
        elif c in "]}" and stack:
            stack.pop()
        elif c == "," and stack:
            if stack[-1][0] == "list":
                stack[-1][1] += 1
            else:
                stack[-1][1:] = [None, i + 1]
        elif c == "=" and stack and stack[-1][0] == "table" and stack[-1][1] is None:
            stack[-1][1] = value[stack[-1][2]:i].strip()
    for entry in stack:
        if entry[0] == "list":
            path += f"[{entry[1]}]"
        elif entry[1] is not None:
            for key in _keys(entry[1]):
                path = _join(path, key)
    return path


def dict_path(text: str, line: int, column: int) -> str | None:
    """What line:column (1-based) of `text` (from dumps) holds, as a path into the dict; None if the
    line holds no key (a blank line, past the end)."""
    lines = text.splitlines()
    if not 1 <= line <= len(lines):
        return None
    key_line = re.compile(r"\s*((?:\"(?:[^\"\\]|\\.)*\"|[^=\s\[])+)\s*=\s*")
    table = ""
    arrays: dict[str, int] = {}  # an array of tables (its path, indices resolved) -> its items so far
    open_array = None  # [its path, the index of the next item] while an array runs over several lines
    for n, raw in enumerate(lines[:line], 1):
        s = raw.strip()
        if open_array is not None:
            if s == "]":
                open_array = None
                at = table
            else:
                at = _inside(raw, max(column - 1, 0), f"{open_array[0]}[{open_array[1]}]") if n == line else None
                open_array[1] += 1
            if n == line:
                return at or None
            continue
        header = re.fullmatch(r"(\[\[?)\s*(.+?)\s*\]\]?", s)
        if header:
            table = ""
            keys = _keys(header.group(2))
            for k, key in enumerate(keys):
                table = _join(table, key)
                if k == len(keys) - 1 and header.group(1) == "[[":
                    arrays[table] = arrays.get(table, 0) + 1
                if table in arrays:
                    table += f"[{arrays[table] - 1}]"
            if n == line:
                return table or None
            continue
        m = key_line.match(raw)
        path = table
        if m:
            for key in _keys(m.group(1)):
                path = _join(path, key)
            if raw[m.end():].strip() == "[":
                open_array = [path, 0]
        if n == line:
            return (_inside(raw[m.end():], max(column - 1 - m.end(), 0), path) if m else path) or None
    return None


def located(message: str, text: str, path: str) -> str:
    """The reader's message with each `path:line:column` of the generated TOML replaced by the place in
    the dict it stands for: "scene dict at bodies[0].density"."""
    def at(m: re.Match) -> str:
        where = dict_path(text, int(m.group(1)), int(m.group(2)))
        return f"scene dict at {where}" if where else "scene dict"
    return re.sub(re.escape(path) + r":(\d+):(\d+)", at, message)
