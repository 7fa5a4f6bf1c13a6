"""Make the pictures the in-app manual shows from the screenshots here.

The manual (``resources/manual/<language>.md``, shipped in the wheel) shows one picture of
each guided task; the full step-by-step gallery stays in ``docs/wizards.md``. Each picture
the manuals name as ``images/NAME.png`` is ``docs/screenshots/NAME.png`` reduced to 256
colours (a screenshot of a dialog looks the same and is a fifth of the size), so the wheel
grows by a few tens of kilobytes, not megabytes. Run after ``shoot_wizards.py``:

    QT_QPA_PLATFORM=offscreen python docs/screenshots/manual_pictures.py

The German manual shows German pictures: take the screenshots of the German build into a
folder of their own (``shoot_wizards.py --lang de --out DIR``, see there), then

    QT_QPA_PLATFORM=offscreen python docs/screenshots/manual_pictures.py --lang de DIR

writes ``resources/manual/images/de/NAME.png`` for the pictures ``de.md`` names (the
manual shows the English picture where a language has none of its own).
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

from PySide6.QtCore import Qt
from PySide6.QtGui import QGuiApplication, QImage

HERE = Path(__file__).resolve().parent
MANUALS = HERE.parents[1] / "resources" / "manual"
PICTURE = re.compile(r"\]\(images/([\w-]+\.png)\)")


def pictures(language: str = "") -> list[str]:
    """Every picture a manual names (``language``'s manual only, when given), once."""
    names: list[str] = []
    for manual in sorted(MANUALS.glob(f"{language}.md" if language else "*.md")):
        names += [n for n in PICTURE.findall(manual.read_text("utf-8")) if n not in names]
    return names


def main() -> int:
    _app = QGuiApplication(sys.argv)
    out, shots, language = MANUALS / "images", HERE, ""
    if "--lang" in sys.argv:
        at = sys.argv.index("--lang")
        language, shots = sys.argv[at + 1], Path(sys.argv[at + 2])
        out = out / language
    out.mkdir(exist_ok=True)
    for name in pictures(language):
        shot = QImage(str(shots / name))
        if shot.isNull():
            print(f"no screenshot {shots / name}", file=sys.stderr)
            return 1
        small = shot.convertToFormat(QImage.Format.Format_Indexed8,
                                     Qt.ImageConversionFlag.ThresholdDither
                                     | Qt.ImageConversionFlag.AvoidDither)
        small.save(str(out / name), "PNG", 0)  # 0: the smallest file
        print(f"{out / name}: {(out / name).stat().st_size} bytes")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
