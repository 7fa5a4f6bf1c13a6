"""The inspector's form: titles, parameter rows in grids, the collapsible Details section.

One row per parameter (its name, the editor, unit and layout, an error line beneath); the
editors and error labels are kept by field name so the inspector (and tests) find them.
"""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtGui import QFont
from PySide6.QtWidgets import (
    QGridLayout,
    QLabel,
    QToolButton,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.i18n import translate
from pdcp_studio.model import parameters as params

ERROR_STYLE = "color: #b91c1c;"
DIM_STYLE = "color: #66707b;"


def _tr(text: str) -> str:
    return translate("Inspector", text)


def selectable(text: str) -> QLabel:
    """A read-only value the user can select and copy."""
    label = QLabel(text)
    label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
    label.setWordWrap(True)
    return label


class Form:
    """Builds one form's rows; ``editors`` and ``errors`` are the inspector's tables by
    field name (filled here, cleared by the inspector for each new form)."""

    def __init__(self, editors: dict[str, QWidget], errors: dict[str, QLabel]) -> None:
        self.editors = editors
        self.errors = errors

    def title(self, box: QVBoxLayout, title: str, subtitle: str) -> None:
        t = QLabel(title)
        f = QFont(t.font())
        f.setBold(True)
        f.setPointSizeF(f.pointSizeF() * 1.15)
        t.setFont(f)
        t.setWordWrap(True)
        box.addWidget(t)
        s = selectable(subtitle)
        s.setStyleSheet(DIM_STYLE)
        box.addWidget(s)

    def grid(self, box: QVBoxLayout, live: bool) -> QGridLayout:
        """A grid of parameter rows (``live``: with the note that an edit is staged)."""
        if live:
            note = QLabel(_tr("Live bus: an edit here is a pending change (one undo "
                              "step); Write to prosthesis writes the pending changes "
                              "in one transaction."))
            note.setWordWrap(True)
            note.setStyleSheet("color: #b45309;")
            box.addWidget(note)
        grid = QGridLayout()
        grid.setHorizontalSpacing(8)
        grid.setVerticalSpacing(3)
        grid.setColumnStretch(1, 1)
        for col, text in enumerate(("Parameter", "Value")):
            h = QLabel(_tr("<b>{text}</b>").format(text=text))
            grid.addWidget(h, 0, col)
        box.addLayout(grid)
        return grid

    def plain_grid(self, box: QVBoxLayout, live: bool) -> QGridLayout:
        """:meth:`grid` whose rows show names only (their encoding in the tooltip)."""
        grid = self.grid(box, live)
        grid.setProperty("plainRows", True)
        return grid

    def details(self, box: QVBoxLayout, expanded: bool = False) -> QGridLayout:
        """A collapsible "Details" section (collapsed at first): the engineer's encoding,
        codes and numbers, one click away from what a prosthetist sets."""
        button = QToolButton()
        button.setText(_tr("Details for engineers"))
        button.setCheckable(True)
        button.setChecked(expanded)
        button.setToolButtonStyle(Qt.ToolButtonStyle.ToolButtonTextBesideIcon)
        button.setArrowType(Qt.ArrowType.DownArrow if expanded else Qt.ArrowType.RightArrow)
        button.setAutoRaise(True)
        body = QWidget()
        grid = QGridLayout(body)
        grid.setContentsMargins(0, 0, 0, 0)
        grid.setHorizontalSpacing(8)
        grid.setVerticalSpacing(3)
        grid.setColumnStretch(1, 1)
        body.setVisible(expanded)

        def toggle(on: bool) -> None:
            body.setVisible(on)
            button.setArrowType(Qt.ArrowType.DownArrow if on else Qt.ArrowType.RightArrow)

        button.toggled.connect(toggle)
        box.addWidget(button)
        box.addWidget(body)
        self.editors["details"] = button
        return grid

    def row(self, grid: QGridLayout, spec: params.ParameterSpec | None, name: str,
            field: str, editor: QWidget, meta: str | None = None) -> None:
        """One parameter: name, editor, unit and layout; an error line below it."""
        row = grid.rowCount()
        if meta is None:
            meta = " · ".join(x for x in (spec.unit if spec else "",
                                           spec.layout if spec else "PDCP Studio only") if x)
        title = spec.name if spec else name
        plain = bool(grid.property("plainRows")) and bool(title)
        if plain:  # a prosthetist's setting: the encoding is the engineer's, in the tooltip
            label = QLabel(title)
        elif title:
            label = QLabel(_tr("{title}<br><span style='color:#66707b; font-size:small'>"
                               "{meta}</span>").format(title=title, meta=meta))
        else:
            label = QLabel(_tr("<span style='color:#66707b; font-size:small'>{meta}</span>"
                               ).format(meta=meta))
        label.setWordWrap(True)
        label.setMinimumWidth(90)
        label.setMaximumWidth(130)
        tip = f"parameter {spec.id}: {spec.doc}" if spec and spec.doc else (
            f"parameter {spec.id}" if spec else "kept by PDCP Studio only")
        if spec and not spec.writable:
            tip += " (read-only)"
        if plain and meta:
            tip += f"\n{meta}"
        label.setToolTip(tip)
        grid.addWidget(label, row, 0, Qt.AlignmentFlag.AlignTop)
        grid.addWidget(editor, row, 1)
        err = QLabel()
        err.setStyleSheet(ERROR_STYLE)
        err.setWordWrap(True)
        err.hide()
        grid.addWidget(err, row + 1, 1)
        self.editors[field] = editor
        self.errors[field] = err
