"""Flash and RAM per module from a GNU ld map file: `python3 tools/map_sizes.py MAP arm|avr`.

Flash = .text + .rodata + .data (its initial values); RAM = .data + .bss. On the AVR string
literals (.rodata) live in RAM too. Prints one row per source file and the totals, as
firmware/README.md shows them.
"""
import re
import sys
from collections import defaultdict

path, target = sys.argv[1], sys.argv[2]
flash = defaultdict(int)
ram = defaultdict(int)
pending = None
discarded = False
for line in open(path, encoding="utf-8", errors="replace"):
    if line.startswith("Discarded input sections"):
        discarded = True
    elif line.startswith("Memory Configuration") or line.startswith("Linker script"):
        discarded = False
    if discarded:
        continue
    m = re.match(r"^ (\.[\w.$]+|COMMON)\s*$", line)
    if m:
        pending = m.group(1)
        continue
    m = re.match(r"^ (\.[\w.$]+|COMMON)?\s+0x([0-9a-f]+)\s+0x([0-9a-f]+)\s+(\S+\.o\)?)\s*$",
                 line)
    if not m:
        pending = None
        continue
    section = m.group(1) or pending
    pending = None
    addr, size, obj = int(m.group(2), 16), int(m.group(3), 16), m.group(4)
    if not section or not size or addr == 0 and target == "arm" and section.startswith(".bss"):
        continue
    name = re.sub(r"^.*obj/", "", obj).replace(".o", ".c")
    if "obj/" not in obj:
        name = "(libc/libgcc)"
    if section.startswith((".text", ".rodata", ".progmem", ".vectors", ".init", ".fini")):
        flash[name] += size
        if target == "avr" and section.startswith(".rodata"):
            ram[name] += size
    elif section.startswith(".data"):
        flash[name] += size
        ram[name] += size
    elif section.startswith((".bss", "COMMON")):
        ram[name] += size
names = sorted(set(flash) | set(ram), key=lambda n: (n.startswith("("), n))
print(f"{target}: {'module':<28} {'flash':>7} {'RAM':>7}")
for n in names:
    print(f"{target}: {n:<28} {flash[n]:>7} {ram[n]:>7}")
print(f"{target}: {'total':<28} {sum(flash.values()):>7} {sum(ram.values()):>7}")
