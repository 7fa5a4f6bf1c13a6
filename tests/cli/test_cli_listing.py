"""`print` and `info` on the shipped appendix D rig; exit statuses of the contract."""

import subprocess
import sys

from pdcp_studio.cli.main import main


def test_print_lists_what_appendix_d_lists(capsys, systems_dir):
    assert main(["print", "--system", str(systems_dir / "appendix-d.json")]) == 0
    out = capsys.readouterr().out
    for line in ["n_devices: 3", "n_missing_devices: 0", "n_input_channels: 4",
                 "n_output_channels: 4", "n_channel_links: 3",
                 "type: 7200", "profile: 2200", "source vid: FFFF", "source ci: FF",
                 "source type: 5000", "source profile: 2120", "terminal profile: 1110",
                 "required ichans: 32", "required ichans: 64", "serial number: 6"]:
        assert line in out, line


def test_info_is_short(capsys, systems_dir):
    assert main(["info", "--system", str(systems_dir / "transradial.json")]) == 0
    out = capsys.readouterr().out
    assert out.splitlines()[0].startswith("4 devices (0 missing)")
    assert "Hand" in out


def test_bad_system_file_exits_2_naming_file_and_path(tmp_path, capsys):
    f = tmp_path / "bad.json"
    f.write_text('{"format": "pdcp-system/1", "devices": [{"vid": 1, "pid": 1}]}')
    assert main(["info", "--system", str(f)]) == 2
    err = capsys.readouterr().err
    assert "bad.json" in err and "devices[0]" in err and "serial" in err


def test_missing_file_exits_2(tmp_path, capsys):
    assert main(["print", "--system", str(tmp_path / "nope.json")]) == 2
    assert "nope.json" in capsys.readouterr().err


def test_cli_does_not_import_qt():
    code = ("import sys, pdcp_studio.cli.main as m; m.build_parser(); "
            "assert 'PySide6' not in sys.modules, 'Qt'; "
            "assert 'networkx' not in sys.modules, 'networkx'; "
            "assert 'can' not in sys.modules, 'python-can'")
    subprocess.run([sys.executable, "-c", code], check=True)
