"""The plug-in's help (ParaView's "?"): the build compiles every proxy's XML <Documentation>
into a Qt help file (paraview_add_plugin's XML_DOCUMENTATION), which the plug-in embeds. A .qch
file is an SQLite database whose FileDataTable holds each page compressed as Qt's qCompress
does (a 4-byte big-endian length, then zlib); this reads it without Qt and requires, for every
filter, reader and writer proxy of paraview_plugin/*.xml its own page, named as ParaView's "?"
looks it up (GROUP.NAME.html; readers under "sources"), whose text holds its label and the
first words of its long help and of one property's documentation. (ParaView 5.11 splits the
pages apart at CMake list separators and an unbalanced "[" in a documentation, as in a
half-open "[0, 2 pi)", glues the following pages into one: this finds that.)

usage: TestPluginHelp.py QCH_FILE PLUGIN_XML_DIR"""
import glob
import html
import os
import re
import sqlite3
import sys
import xml.etree.ElementTree
import zlib

qch, xml_dir = sys.argv[1:3]
failures = []
if not os.path.isfile(qch):
    sys.exit(f"FAILED: no help file {qch}")
database = sqlite3.connect(f"file:{qch}?mode=ro", uri=True)
names = dict(database.execute("SELECT FileId, Name FROM FileNameTable"))
pages = {}
for file_id, data in database.execute("SELECT Id, Data FROM FileDataTable"):
    if file_id in names and names[file_id].endswith(".html"):
        text = zlib.decompress(bytes(data)[4:]).decode("utf-8", "replace")
        pages[names[file_id]] = " ".join(html.unescape(re.sub(r"<[^>]+>", " ", text)).split())


def words(text, count=8):
    return " ".join(text.split()[:count])


checked = 0
for path in sorted(glob.glob(os.path.join(xml_dir, "*.xml"))):
    for group in xml.etree.ElementTree.parse(path).getroot():
        for proxy in group:
            documentation = proxy.find("Documentation")
            if documentation is None or proxy.get("label") is None:
                continue
            label = proxy.get("label")
            long_help = words(documentation.get("long_help", ""))
            prop = next((p for p in proxy if p.find("Documentation") is not None and
                         (p.find("Documentation").text or "").strip()), None)
            wanted = [label, long_help] + ([words(prop.find("Documentation").text)] if prop else [])
            group_name = "sources" if group.get("name") == "readers" else group.get("name")
            page = f"{group_name}.{proxy.get('name')}.html"
            text = pages.get(page, "")
            missing = [w for w in wanted if w not in text]
            if page not in pages or missing:
                failures.append(f"{page}: " + (f"lacks {missing}" if page in pages else
                                               f"no such page (pages: {sorted(pages)})"))
            else:
                checked += 1
                print(f"{proxy.get('name')}: {page}")
if checked < 8:
    failures.append(f"only {checked} proxies have pages (expected the readers, writers, filters)")
for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
