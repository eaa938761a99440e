"""Report databases as text, in the layout KLayout saves them: the pieces the direct writers
(gauge_output.write_report, selection_output.write_report) share, and one database from two
saved ones.

flow.lyrdb is gauges.lyrdb (up to half a
million items on a full layer) followed by the selection's and the split's categories and items
(selection_output.write_report). Loading the gauges into KLayout only to save them again took a
fifth of a mid-size flow.

Both files are in the layout KLayout saves (and gauge_output.write_report imitates): header,
<tags>, <categories>, <cells>, <items>, one element per line. The result is what KLayout saves
after loading the first file and adding the second's contents through its API (tested): the
first's tags (declared, then those its items' values name, "[#name]"), then the second's new
ones; the categories, then the items, of the first and then of the second; the first's cells
(both name the same single top cell). The first file's items must all name the same values
(as write_report's do): its tags are taken from its first item, and the rest is copied as bytes."""
import re
from xml.sax import saxutils

ITEM_END = "   </values>\n  </item>\n"
END = " </items>\n</report-database>\n"

_SECTIONS = ("tags", "categories", "cells", "items")
_ITEMS_END = b" </items>\n"
_TAIL = END.encode()
_VALUE_TAG = re.compile(rb"<value>\[#?([^\]]+)\]")
_TAG = re.compile(rb"  <tag>\n   <name>([^<]*)</name>\n.*?  </tag>\n", re.S)


def head(source, generator, cell_name):
    """The lines before <tags>."""
    esc = saxutils.escape
    return ('<?xml version="1.0" encoding="utf-8"?>\n<report-database>\n <description/>\n%s'
            " <generator>%s</generator>\n <top-cell>%s</top-cell>\n"
            % (" <original-file>%s</original-file>\n" % esc(source) if source else " <original-file/>\n",
               esc(generator), esc(cell_name)))


def tag(name):
    """A tag's entry in <tags>."""
    return "  <tag>\n   <name>%s</name>\n   <description/>\n  </tag>\n" % name


def cells(cell_name):
    """The <cells> block of a database with one top cell."""
    return (" <cells>\n  <cell>\n   <name>%s</name>\n   <variant/>\n   <references>\n   </references>\n"
            "  </cell>\n </cells>\n" % saxutils.escape(cell_name))


def item_head(tags, category, cell):
    """An item's lines up to its values; `cell` escaped already."""
    return ("  <item>\n   %s\n   <category>%s</category>\n   <cell>%s</cell>\n   <visited>false</visited>\n"
            "   <multiplicity>1</multiplicity>\n   <image/>\n   <values>\n"
            % ("<tags>%s</tags>" % ",".join(tags) if tags else "<tags/>", category, cell))


def _blocks(f):
    """Reads the header and the tags, categories and cells blocks from an open file, and the
    items' opening line: (header, {section: inner bytes})."""
    head, inner, name, lines = b"", {}, None, []
    for line in f:
        if name is None:
            opening = next((s for s in _SECTIONS if line == b" <%s>\n" % s.encode()), None)
            if opening is None:
                head += line if not inner else b""
                continue
            name, lines = opening, []
            if name == "items":
                return head, inner
        elif line == b" </%s>\n" % name.encode():
            inner[name], name = b"".join(lines), None
        else:
            lines.append(line)
    raise ValueError("not a report database as KLayout saves it: %s" % f.name)


def _tags(inner):
    return [(m.group(1), m.group(0)) for m in _TAG.finditer(inner)]


def merge(first, second, out, generator):
    """Writes `out`: the report database `first` followed by `second`'s contents (paths), with
    `generator`."""
    with open(first, "rb") as f, open(second, "rb") as g:
        _, b = _blocks(g)
        b_start = g.tell()
        b_end = g.seek(0, 2) - len(_TAIL)
        g.seek(b_end)
        if b_end < b_start or g.read() != _TAIL:
            raise ValueError("not a report database as KLayout saves it: %s" % second)
        with open(out, "wb") as o:
            head, a = _blocks(f)
            start = f.tell()
            first_item = b""
            for line in f:
                first_item += line
                if line in (b"  </item>\n", _ITEMS_END):
                    break
            size = f.seek(0, 2)
            f.seek(size - len(_TAIL))
            if f.read() != _TAIL:
                raise ValueError("not a report database as KLayout saves it: %s" % first)
            head = re.sub(rb" <generator>[^<]*</generator>\n",
                          lambda m: b" <generator>%s</generator>\n" % generator.encode(), head, 1)
            tags = _tags(a["tags"])
            names = [n for n, _ in tags]
            for n in _VALUE_TAG.findall(first_item):
                if n not in names:
                    names.append(n)
                    tags.append((n, tag(n.decode()).encode()))
            tags += [(n, e) for n, e in _tags(b["tags"]) if n not in names]
            o.write(head)
            o.write(b" <tags>\n%s </tags>\n" % b"".join(e for _, e in tags))
            o.write(b" <categories>\n%s%s </categories>\n" % (a["categories"], b["categories"]))
            o.write(b" <cells>\n%s </cells>\n <items>\n" % a["cells"])
            _copy(f, start, size - len(_TAIL), o)  # the first's items, as they are
            _copy(g, b_start, b_end, o)  # then the second's (both can be hundreds of MB)
            o.write(_TAIL)


def _copy(f, start, end, o):
    f.seek(start)
    left = end - start
    while left > 0:
        chunk = f.read(min(left, 1 << 22))
        o.write(chunk)
        left -= len(chunk)
