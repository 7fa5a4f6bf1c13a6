"""Issue 28 item 2: the fitting report prints the fitting history's anchor — the entry and hash
the last change wrote to the prosthesis — in its technical detail, not in the body."""

from __future__ import annotations

from pdcp_studio.storage import system_file


def test_the_report_prints_the_fitting_history_anchor_in_its_technical_detail(systems_dir):
    from pdcp_studio.app.report import FittingInfo, report_html
    from pdcp_studio.storage.profile_trees import load_profile_trees, tree_for

    system = system_file.load_path(systems_dir / "transradial.json")
    tree = tree_for(load_profile_trees(user_dir=False), system)
    digest = "ab" * 32
    info = FittingInfo("P-1", "A. Prosthetist", None, "sim:transradial",
                       [{"id": 11, "action": "apply clear", "hash": "cd" * 32},
                        {"id": 12, "action": "apply clear", "hash": digest}])
    html = report_html(system, tree, fitting=info, checksum=0x1234)
    body, _, detail = html.partition("Technical detail")
    assert f"entry 12, hash {digest}" in detail and digest not in body
    assert "Fitting history anchor in the prosthesis" in detail
    bare = report_html(system, tree, fitting=FittingInfo("P-1"), checksum=0x1234)
    assert "Fitting history anchor" not in bare
