<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="de_DE" sourcelanguage="en_GB">
    <context>
        <name>AddLinkDialog</name>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="205" />
            <source>Add a link</source>
            <translation>Eine Verbindung hinzufügen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="208" />
            <source>From (output)</source>
            <translation>Von (Ausgang)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="209" />
            <source>To (input)</source>
            <translation>Nach (Eingang)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="231" />
            <source>Type and profile are numbers from 0 to 0xFFFF (write hex as 0x2110).</source>
            <translation>Typ und Profil sind Zahlen von 0 bis 0xFFFF (hexadezimal als 0x2110 schreiben).</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="235" />
            <source>A link joins two different channels.</source>
            <translation>Eine Verbindung verbindet zwei verschiedene Kanäle.</translation>
        </message>
    </context>
    <context>
        <name>Autosaver</name>
        <message>
            <location filename="../../pdcp_studio/app/recovery.py" line="210" />
            <source>Autosave: {err}</source>
            <translation>Automatisches Sichern: {err}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/recovery.py" line="224" />
            <source>Autosave: {msg}</source>
            <translation>Automatisches Sichern: {msg}</translation>
        </message>
    </context>
    <context>
        <name>WindowBus</name>
        <message>
            <location filename="../../pdcp_studio/app/window_bus.py" line="38" />
            <source>Some bus panels are unavailable: {err}</source>
            <translation>Einige Bus-Ansichten sind nicht verfügbar: {err}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_bus.py" line="56" />
            <source>Live plot</source>
            <translation>Live-Verlauf</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_bus.py" line="70" />
            <source>Simulator</source>
            <translation>Simulator</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_bus.py" line="138" />
            <source>Read configuration: connect to a bus first</source>
            <translation>Konfiguration lesen: zuerst mit einem Bus verbinden</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_bus.py" line="156" />
            <source>Cancelling…</source>
            <translation>Wird abgebrochen…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_bus.py" line="198" />
            <source>Write configuration</source>
            <translation>Konfiguration schreiben</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_bus.py" line="198" />
            <source>connect to a bus first</source>
            <translation>zuerst mit einem Bus verbinden</translation>
        </message>
        <message>
            <source>Scanning the bus…</source>
            <translation>Lese den Bus…</translation>
        </message>
        <message>
            <source>Bus events</source>
            <translation>Busereignisse</translation>
        </message>
        <message>
            <source>Scan finished: {devices}, {links}</source>
            <translation>Lesen beendet: {devices}, {links}</translation>
        </message>
        <message>
            <source>Read the arbitrator's stored configuration: {configurations}, {links} — Find replacements and Start-up now use it</source>
            <translation>Gespeicherte Konfiguration des Arbiters gelesen: {configurations}, {links} — Ersatz finden und Hochlauf verwenden sie jetzt</translation>
        </message>
        <message numerus="yes">
            <source>%n device(s)</source>
            <translation>
                <numerusform>%n Gerät</numerusform>
                <numerusform>%n Geräte</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>%n link(s)</source>
            <translation>
                <numerusform>%n Verbindung</numerusform>
                <numerusform>%n Verbindungen</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>%n configuration(s)</source>
            <translation>
                <numerusform>%n Konfiguration</numerusform>
                <numerusform>%n Konfigurationen</numerusform>
            </translation>
        </message>
    </context>
    <context>
        <name>BusScene</name>
        <message numerus="yes">
            <source>Removed %n link(s)</source>
            <translation>
                <numerusform>%n Verbindung entfernt</numerusform>
                <numerusform>%n Verbindungen entfernt</numerusform>
            </translation>
        </message>
        <message>
            <source>Input {n} must be connected: a channel of this device that is in use needs it. Connect a source to it, or let Autoconfigure do it.</source>
            <translation>Eingang {n} muss verbunden sein: ein benutzter Kanal dieses Geräts braucht ihn. Verbinden Sie eine Quelle damit oder lassen Sie die Autokonfiguration das tun.</translation>
        </message>
        <message>
            <source>Input {n} drives a part of the prosthesis but nothing feeds it, so that part will not move. Connect a matching output, or let Autoconfigure do it.</source>
            <translation>Eingang {n} steuert ein Teil der Prothese, bekommt aber keine Daten, daher bewegt sich dieses Teil nicht. Verbinden Sie einen passenden Ausgang oder lassen Sie die Autokonfiguration das tun.</translation>
        </message>
        <message>
            <source>{a} drives a part of the prosthesis but nothing feeds it, so that part will not move. Autoconfigure is off on this prosthesis, so it will not link it on its own: connect a matching output.</source>
            <translation>{a} steuert ein Teil der Prothese, bekommt aber keine Daten, daher bewegt sich dieses Teil nicht. Die Autokonfiguration ist an dieser Prothese aus, sie verbindet es also nicht von selbst: verbinden Sie einen passenden Ausgang.</translation>
        </message>
        <message>
            <source>One output feeds several inputs that each need it for themselves. Keep one of these links and remove the others.</source>
            <translation>Ein Ausgang speist mehrere Eingänge, die ihn jeweils für sich allein brauchen. Behalten Sie eine dieser Verbindungen und entfernen Sie die anderen.</translation>
        </message>
        <message>
            <source>Conflict: this output also feeds another input that needs it for itself. Keep one of these links and remove the others.</source>
            <translation>Konflikt: dieser Ausgang speist auch einen anderen Eingang, der ihn für sich allein braucht. Behalten Sie eine dieser Verbindungen und entfernen Sie die anderen.</translation>
        </message>
        <message>
            <source>This link carries no data: a device at one of its ends is not on the bus. Plug the device in, or remove the link.</source>
            <translation>Diese Verbindung überträgt keine Daten: ein Gerät an einem ihrer Enden ist nicht am Bus. Stecken Sie das Gerät ein oder entfernen Sie die Verbindung.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/scene.py" line="149" />
            <source>Pending removal (still on the prosthesis): {link}</source>
            <extracomment>A link counts as "live" this long after its output's last data frame. Ghosts of links on the prosthesis that the project removes (pending removals). The outcome of the last link drag: (link or None, refusal reason or "").</extracomment>
            <translation>Entfernen vorgemerkt (noch auf der Prothese): {link}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/scene.py" line="365" />
            <source>Drag from {ref} to {what} to link them</source>
            <translation>Von {ref} zu {what} ziehen, um sie zu verbinden</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/scene.py" line="410" />
            <source>Link cancelled: release over a port to link</source>
            <translation>Verbinden abgebrochen: über einem Anschluss loslassen, um zu verbinden</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/scene.py" line="417" />
            <source>Cannot link {a} → {b}: {reason}</source>
            <translation>{a} → {b} kann nicht verbunden werden: {reason}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/scene.py" line="424" />
            <source>Linked {v0} → {v1}</source>
            <translation>Verbunden: {v0} → {v1}</translation>
        </message>
        <message>
            <source>Cannot link: {0}</source>
            <translation>Kann nicht verbunden werden: {0}</translation>
        </message>
        <message>
            <source>Release to link {0} → {1}</source>
            <translation>Loslassen, um {0} → {1} zu verbinden</translation>
        </message>
        <message>
            <source>Drag from {channel} to an input to link them</source>
            <translation>Von {channel} zu einem Eingang ziehen, um sie zu verbinden</translation>
        </message>
        <message>
            <source>Drag from {channel} to an output to link them</source>
            <translation>Von {channel} zu einem Ausgang ziehen, um sie zu verbinden</translation>
        </message>
    </context>
    <context>
        <name>CanPage</name>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="211" />
            <source>(interface default)</source>
            <translation>(Vorgabe der Schnittstelle)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="220" />
            <source>Interface</source>
            <translation>Schnittstelle</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="221" />
            <source>Channel</source>
            <translation>Kanal</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="222" />
            <source>Bitrate (bit/s)</source>
            <translation>Bitrate (bit/s)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="233" />
            <source>Found: {v0}</source>
            <translation>Gefunden: {v0}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="235" />
            <source>No CAN interface found</source>
            <translation>Keine CAN-Schnittstelle gefunden</translation>
        </message>
        <message>
            <source>No CAN adapter found. Check that it is plugged in and its driver is installed, or type the interface and channel.</source>
            <translation>Kein CAN-Adapter gefunden. Prüfen Sie, ob er eingesteckt und sein Treiber installiert ist, oder geben Sie Schnittstelle und Kanal ein.</translation>
        </message>
        <message>
            <source>Found {n}: {which}</source>
            <translation>{n} gefunden: {which}</translation>
        </message>
        <message numerus="yes">
            <source>%n CAN channel(s)</source>
            <translation>
                <numerusform>%n CAN-Kanal</numerusform>
                <numerusform>%n CAN-Kanäle</numerusform>
            </translation>
        </message>
    </context>
    <context>
        <name>ChannelDialog</name>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="132" />
            <source>Channel type</source>
            <extracomment>Where the prosthesis to fit against comes from: () → (system or None, its name).</extracomment>
            <translation>Kanaltyp</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="133" />
            <source>Channel profile</source>
            <translation>Kanalprofil</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="151" />
            <source>Type and profile are numbers from 0 to 0xFFFF (write hex as 0x2110).</source>
            <translation>Typ und Profil sind Zahlen von 0 bis 0xFFFF (hexadezimal als 0x2110 schreiben).</translation>
        </message>
    </context>
    <context>
        <name>CompareDialog</name>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="54" />
            <source>On screen</source>
            <translation>Am Bildschirm</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="77" />
            <source>in all</source>
            <translation>in allen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="78" />
            <source>present</source>
            <translation>vorhanden</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="80" />
            <source>only in {0}</source>
            <translation>nur in {0}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="81" />
            <source>in {0}</source>
            <translation>in {0}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="82" />
            <source> and </source>
            <translation> und </translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="157" />
            <source>Compare configurations</source>
            <translation>Konfigurationen vergleichen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="177" />
            <source>Open file…</source>
            <extracomment>The stored configurations behind the file and arbitrator columns (when known).</extracomment>
            <translation>Datei öffnen…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="179" />
            <source>Read arbitrator</source>
            <translation>Arbiter lesen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="183" />
            <source>Connect to a bus to read its arbitrator</source>
            <translation>Mit einem Bus verbinden, um seinen Arbiter zu lesen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="184" />
            <source>Differences only</source>
            <translation>Nur Unterschiede</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="199" />
            <source>&lt;b&gt;Error:&lt;/b&gt; {msg}</source>
            <translation>&lt;b&gt;Fehler:&lt;/b&gt; {msg}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="239" />
            <source>Reading {name}…</source>
            <translation>{name} wird gelesen…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="255" />
            <source>Not connected to a bus: there is no arbitrator to read</source>
            <translation>Nicht mit einem Bus verbunden: kein Arbiter zum Lesen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="261" />
            <source>Reading the arbitrator's stored configuration…</source>
            <translation>Die gespeicherte Konfiguration des Arbiters wird gelesen…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="268" />
            <source>Reading the arbitrator: {message}</source>
            <translation>Arbiter lesen: {message}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="275" />
            <source>Compare with a file</source>
            <translation>Mit einer Datei vergleichen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="276" />
            <source>Configurations and systems (*.pdcfg *.json);;All files (*)</source>
            <translation>Konfigurationen und Systeme (*.pdcfg *.json);;Alle Dateien (*)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="301" />
            <source>Output</source>
            <translation>Ausgang</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="301" />
            <source>Input</source>
            <translation>Eingang</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="301" />
            <source>Status</source>
            <translation>Zustand</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/compare_dialog.py" line="328" />
            <source>none</source>
            <translation>keine</translation>
        </message>
        <message>
            <source>{0}: {1}</source>
            <translation>{0}: {1}</translation>
        </message>
        <message numerus="yes">
            <source>%n link(s)</source>
            <translation>
                <numerusform>%n Verbindung</numerusform>
                <numerusform>%n Verbindungen</numerusform>
            </translation>
        </message>
        <message>
            <source>Technical details</source>
            <translation>Technische Details</translation>
        </message>
        <message>
            <source>Where they differ:</source>
            <translation>Wo sie sich unterscheiden:</translation>
        </message>
        <message numerus="yes">
            <source>and %n more</source>
            <translation>
                <numerusform>und %n weitere</numerusform>
                <numerusform>und %n weitere</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>The stored configurations of {0} and of the arbitrator differ in %n place(s).</source>
            <translation>
                <numerusform>Die gespeicherten Konfigurationen in {0} und im Arbiter unterscheiden sich an %n Stelle.</numerusform>
                <numerusform>Die gespeicherten Konfigurationen in {0} und im Arbiter unterscheiden sich an %n Stellen.</numerusform>
            </translation>
        </message>
        <message>
            <source>The stored configurations of {0} and of the arbitrator are the same, record by record.</source>
            <translation>Die gespeicherten Konfigurationen in {0} und im Arbiter sind Eintrag für Eintrag gleich.</translation>
        </message>
        <message>
            <source>the file</source>
            <translation>der Datei</translation>
        </message>
    </context>
    <context>
        <name>ConfigDocument</name>
        <message>
            <location filename="../../pdcp_studio/app/config_document.py" line="93" />
            <source>untitled.pdcfg</source>
            <translation>unbenannt.pdcfg</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_document.py" line="128" />
            <source>Add configuration</source>
            <translation>Konfiguration hinzufügen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_document.py" line="136" />
            <source>Duplicate configuration %1</source>
            <translation>Konfiguration %1 duplizieren</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_document.py" line="146" />
            <source>Remove configuration %1</source>
            <translation>Konfiguration %1 entfernen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_document.py" line="157" />
            <source>Move configuration %1</source>
            <translation>Konfiguration %1 verschieben</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_document.py" line="164" />
            <source>Add link</source>
            <translation>Verbindung hinzufügen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_document.py" line="172" />
            <source>Remove link</source>
            <translation>Verbindung entfernen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_document.py" line="174" />
            <source>Remove links</source>
            <translation>Verbindungen entfernen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_document.py" line="185" />
            <source>Edit channel %1</source>
            <translation>Kanal %1 bearbeiten</translation>
        </message>
    </context>
    <context>
        <name>ConfigWindow</name>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="266" />
            <source>Add</source>
            <translation>Hinzufügen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="267" />
            <source>Duplicate</source>
            <translation>Duplizieren</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="268" />
            <source>Remove</source>
            <translation>Entfernen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="269" />
            <location filename="../../pdcp_studio/app/config_view.py" line="412" />
            <source>Move up</source>
            <translation>Nach oben</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="270" />
            <location filename="../../pdcp_studio/app/config_view.py" line="413" />
            <source>Move down</source>
            <translation>Nach unten</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="279" />
            <source>Configurations</source>
            <translation>Konfigurationen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="283" />
            <source>At start-up the arbitrator picks the configuration that best fits the devices present; on a tie, the higher one.</source>
            <translation>Beim Hochlauf wählt der Arbiter die Konfiguration, die am besten zu den vorhandenen Geräten passt; bei Gleichstand die höhere.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="297" />
            <source>Link</source>
            <translation>Verbindung</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="297" />
            <source>From (output)</source>
            <translation>Von (Ausgang)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="297" />
            <location filename="../../pdcp_studio/app/config_view.py" line="298" />
            <source>Type</source>
            <translation>Typ</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="297" />
            <location filename="../../pdcp_studio/app/config_view.py" line="298" />
            <source>Profile</source>
            <translation>Profil</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="298" />
            <source>To (input)</source>
            <translation>Nach (Eingang)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="306" />
            <location filename="../../pdcp_studio/app/config_view.py" line="414" />
            <source>Add link…</source>
            <translation>Verbindung hinzufügen…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="307" />
            <location filename="../../pdcp_studio/app/config_view.py" line="403" />
            <source>Remove link</source>
            <translation>Verbindung entfernen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="308" />
            <source>Edit output channel…</source>
            <translation>Ausgangskanal bearbeiten…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="309" />
            <source>Edit input channel…</source>
            <translation>Eingangskanal bearbeiten…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="336" />
            <location filename="../../pdcp_studio/app/config_view.py" line="419" />
            <source>Fit to the prosthesis in the main window</source>
            <translation>An die Prothese im Hauptfenster anpassen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="337" />
            <location filename="../../pdcp_studio/app/config_view.py" line="421" />
            <source>Fit to a system file…</source>
            <translation>An eine Systemdatei anpassen…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="348" />
            <source>Checks</source>
            <translation>Prüfungen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="349" />
            <source>Fit</source>
            <translation>Anpassen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="384" />
            <source>&amp;File</source>
            <extracomment>Started when the prosthesis changes (names and fit follow it, debounced).</extracomment>
            <translation>&amp;Datei</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="385" />
            <source>&amp;Save</source>
            <translation>&amp;Speichern</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="388" />
            <source>Save &amp;as…</source>
            <translation>Speichern &amp;unter…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="391" />
            <source>&amp;Close</source>
            <translation>S&amp;chließen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="396" />
            <source>&amp;Edit</source>
            <translation>&amp;Bearbeiten</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="397" />
            <source>&amp;Undo</source>
            <translation>&amp;Rückgängig</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="399" />
            <source>&amp;Redo</source>
            <translation>&amp;Wiederholen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="407" />
            <source>&amp;Configuration</source>
            <translation>&amp;Konfiguration</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="408" />
            <source>Add configuration</source>
            <translation>Konfiguration hinzufügen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="409" />
            <source>Duplicate configuration</source>
            <translation>Konfiguration duplizieren</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="411" />
            <source>Remove configuration</source>
            <translation>Konfiguration entfernen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="418" />
            <source>F&amp;it</source>
            <translation>An&amp;passen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="433" />
            <source>Stored configurations</source>
            <translation>Gespeicherte Konfigurationen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="434" />
            <source> — PDCP Studio</source>
            <translation> — PDCP Studio</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="495" />
            <source>not stored</source>
            <translation>nicht gespeichert</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="519" />
            <source>Nothing to report: the stored links can all be made together and their ends fit each other.</source>
            <translation>Nichts zu melden: Die gespeicherten Verbindungen lassen sich alle zugleich herstellen, und ihre Enden passen zueinander.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="540" />
            <source>No prosthesis to fit to. Open a system file or connect to a bus in the main window, or choose a system file here.</source>
            <translation>Keine Prothese zum Anpassen. Im Hauptfenster eine Systemdatei öffnen oder mit einem Bus verbinden, oder hier eine Systemdatei wählen.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="544" />
            <source>Fitted to %1.</source>
            <translation>An %1 angepasst.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="554" />
            <source>At start-up: %1</source>
            <translation>Beim Hochlauf: %1</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="560" />
            <source>Link %1: %2 → %3
%4</source>
            <translation>Verbindung %1: %2 → %3
%4</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="575" />
            <source>add</source>
            <translation>hinzufügen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="575" />
            <source>remove</source>
            <translation>entfernen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="600" />
            <source>Cannot open</source>
            <translation>Öffnen nicht möglich</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="609" />
            <source>Fit to a system file</source>
            <translation>An eine Systemdatei anpassen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="610" />
            <source>System files (*.json)</source>
            <translation>Systemdateien (*.json)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="670" />
            <source>Stored channel %1</source>
            <translation>Gespeicherter Kanal %1</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="721" />
            <source>Save as</source>
            <translation>Speichern unter</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="722" />
            <source>Stored configurations (*.pdcfg)</source>
            <translation>Gespeicherte Konfigurationen (*.pdcfg)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="729" />
            <source>Cannot save</source>
            <translation>Speichern nicht möglich</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="731" />
            <source>Saved %1</source>
            <translation>%1 gespeichert</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="743" />
            <source>Unsaved changes</source>
            <translation>Ungespeicherte Änderungen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="744" />
            <source>Save the changes to %1?</source>
            <translation>Änderungen an %1 speichern?</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="773" />
            <source>the live bus %1</source>
            <translation>der Live-Bus %1</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="779" />
            <source>the main window</source>
            <translation>das Hauptfenster</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="781" />
            <source>the prosthesis in the main window (%1)</source>
            <translation>die Prothese im Hauptfenster (%1)</translation>
        </message>
        <message>
            <source>Form</source>
            <translation>Form</translation>
        </message>
        <message>
            <source>What it carries</source>
            <translation>Was er trägt</translation>
        </message>
        <message>
            <source>not named in the profile tree</source>
            <translation>im Profilbaum nicht benannt</translation>
        </message>
        <message>
            <source>unknown form</source>
            <translation>unbekannte Form</translation>
        </message>
        <message>
            <source>signed number</source>
            <translation>Zahl mit Vorzeichen</translation>
        </message>
        <message>
            <source>number</source>
            <translation>Zahl</translation>
        </message>
        <message>
            <source>decimal number</source>
            <translation>Dezimalzahl</translation>
        </message>
        <message>
            <source>on/off</source>
            <translation>ein/aus</translation>
        </message>
        <message>
            <source>position</source>
            <translation>Position</translation>
        </message>
        <message>
            <source>speed</source>
            <translation>Geschwindigkeit</translation>
        </message>
        <message>
            <source>acceleration</source>
            <translation>Beschleunigung</translation>
        </message>
        <message>
            <source>other</source>
            <translation>andere</translation>
        </message>
        <message>
            <source>{kind} ({bits} bits), {mode}</source>
            <translation>{kind} ({bits} Bit), {mode}</translation>
        </message>
        <message>
            <source>type {code}</source>
            <translation>Typ {code}</translation>
        </message>
        <message>
            <source>profile {code}</source>
            <translation>Profil {code}</translation>
        </message>
        <message>
            <source>Link {links} joins {a} to its own device. Remove it.</source>
            <translation>Verbindung {links} verbindet {a} mit dem eigenen Gerät. Entfernen Sie sie.</translation>
        </message>
        <message>
            <source>Links {links} store the same link {a} → {b}; it is made once. Remove the extra ones.</source>
            <translation>Die Verbindungen {links} speichern dieselbe Verbindung {a} → {b}; sie wird einmal hergestellt. Entfernen Sie die überzähligen.</translation>
        </message>
        <message>
            <source>{a} is given more than one source (links {links}); only the first would be made. Keep one of them.</source>
            <translation>{a} bekommt mehr als eine Quelle (Verbindungen {links}); nur die erste würde hergestellt. Behalten Sie eine davon.</translation>
        </message>
        <message>
            <source>{a} is stored as an output and as an input (links {links}); a channel is one or the other. Correct the wrong link.</source>
            <translation>{a} ist als Ausgang und als Eingang gespeichert (Verbindungen {links}); ein Kanal ist das eine oder das andere. Korrigieren Sie die falsche Verbindung.</translation>
        </message>
        <message>
            <source>{a} feeds several inputs that each need it for themselves (links {links}). Keep one of these links.</source>
            <translation>{a} speist mehrere Eingänge, die ihn jeweils für sich allein brauchen (Verbindungen {links}). Behalten Sie eine dieser Verbindungen.</translation>
        </message>
        <message>
            <source>{a} is stored with different descriptions in links {links}. Edit the channel so they agree.</source>
            <translation>{a} ist in den Verbindungen {links} unterschiedlich beschrieben. Bearbeiten Sie den Kanal, sodass sie übereinstimmen.</translation>
        </message>
        <message>
            <source>Link {links}: {a} and {b} carry different kinds of signal; {b} may not understand what it is sent.</source>
            <translation>Verbindung {links}: {a} und {b} tragen verschiedene Arten Signal; {b} versteht womöglich nicht, was gesendet wird.</translation>
        </message>
        <message>
            <source>Link {links}: {a} and {b} carry the same kind of signal in different forms; the input adapts to the output.</source>
            <translation>Verbindung {links}: {a} und {b} tragen dieselbe Art Signal in verschiedener Form; der Eingang passt sich dem Ausgang an.</translation>
        </message>
        <message>
            <source>both ends are on the prosthesis: made as stored</source>
            <translation>beide Enden sind an der Prothese: wird wie gespeichert hergestellt</translation>
        </message>
        <message>
            <source>the output</source>
            <translation>der Ausgang</translation>
        </message>
        <message>
            <source>the input</source>
            <translation>der Eingang</translation>
        </message>
        <message>
            <source>{end} is missing</source>
            <translation>{end} fehlt</translation>
        </message>
        <message>
            <source>{end} has the other direction on the prosthesis</source>
            <translation>{end} hat an der Prothese die andere Richtung</translation>
        </message>
        <message>
            <source>replaced by {link} ({similar})</source>
            <translation>ersetzt durch {link} ({similar})</translation>
        </message>
        <message>
            <source>{parts}: no replacement found, the link is not made</source>
            <translation>{parts}: kein Ersatz gefunden, die Verbindung wird nicht hergestellt</translation>
        </message>
        <message>
            <source>Configuration %1 · %2</source>
            <translation>Konfiguration %1 · %2</translation>
        </message>
        <message numerus="yes">
            <source>%n link(s)</source>
            <translation>
                <numerusform>%n Verbindung</numerusform>
                <numerusform>%n Verbindungen</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>%n problem(s) found</source>
            <translation>
                <numerusform>%n Problem gefunden</numerusform>
                <numerusform>%n Probleme gefunden</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>%n configuration(s)</source>
            <translation>
                <numerusform>%n Konfiguration</numerusform>
                <numerusform>%n Konfigurationen</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>%n record(s) from newer firmware or tools kept as they are</source>
            <translation>
                <numerusform>%n Datensatz aus neuerer Firmware oder neueren Werkzeugen unverändert übernommen</numerusform>
                <numerusform>%n Datensätze aus neuerer Firmware oder neueren Werkzeugen unverändert übernommen</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>What start-up would do with this configuration (%n step(s)):</source>
            <translation>
                <numerusform>Was der Hochlauf mit dieser Konfiguration täte (%n Schritt):</numerusform>
                <numerusform>Was der Hochlauf mit dieser Konfiguration täte (%n Schritte):</numerusform>
            </translation>
        </message>
    </context>
    <context>
        <name>ConfirmDialog</name>
        <message>
            <location filename="../../pdcp_studio/app/transaction_flow.py" line="69" />
            <source>This is what will change on the prosthesis. The devices that drive a hand, wrist or elbow are held still while it is written, then it is read back and verified; on any mismatch the prosthesis is put back as it was.</source>
            <translation>Das ändert sich an der Prothese. Die Geräte, die Hand, Handgelenk oder Ellbogen bewegen, werden während des Schreibens stillgehalten; danach wird zurückgelesen und geprüft. Bei jeder Abweichung wird die Prothese in den vorigen Zustand zurückversetzt.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/transaction_flow.py" line="80" />
            <source>Write to prosthesis</source>
            <translation>Auf die Prothese schreiben</translation>
        </message>
        <message>
            <source>Store as the prosthesis's configuration (keeps this after the next power-on)</source>
            <translation>Als Konfiguration der Prothese speichern (bleibt nach dem nächsten Einschalten erhalten)</translation>
        </message>
        <message>
            <source>Working out what the next power-on does…</source>
            <translation>Es wird ermittelt, was das nächste Einschalten bewirkt…</translation>
        </message>
        <message>
            <source>Technical detail</source>
            <translation>Technische Einzelheiten</translation>
        </message>
        <message>
            <source>The change could not be previewed again: {0}</source>
            <translation>Die Änderung konnte nicht erneut angezeigt werden: {0}</translation>
        </message>
    </context>
    <context>
        <name>ConnectDialog</name>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="123" />
            <source>Simulated prosthesis</source>
            <translation>Simulierte Prothese</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="201" />
            <source>CAN interface</source>
            <translation>CAN-Schnittstelle</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="277" />
            <source>Serial host link</source>
            <translation>Serielle Host-Verbindung</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="343" />
            <source>Connect to a bus</source>
            <extracomment>The kinds of bus, in tab order. Add a BusPage subclass here for a new kind.</extracomment>
            <translation>Mit einem Bus verbinden</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="358" />
            <source>Connect</source>
            <translation>Verbinden</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="402" />
            <source>URL: {shown}</source>
            <translation>URL: {shown}</translation>
        </message>
    </context>
    <context>
        <name>Desktop</name>
        <message>
            <location filename="../../pdcp_studio/app/window_desktop.py" line="89" />
            <source>More menus</source>
            <extracomment>What a dropped file is, by suffix. Plan shortcuts, in the order of the Plan menu. The controls that need an accessible name.</extracomment>
            <translation>Weitere Menüs</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_desktop.py" line="90" />
            <source>More tools</source>
            <translation>Weitere Werkzeuge</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_desktop.py" line="91" />
            <source>Select all</source>
            <translation>Alles auswählen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_desktop.py" line="187" />
            <source>Opening capture {name}…</source>
            <translation>Mitschnitt {name} wird geöffnet…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_desktop.py" line="249" />
            <source>Undo</source>
            <translation>Rückgängig</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_desktop.py" line="251" />
            <source>Redo</source>
            <translation>Wiederholen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_desktop.py" line="286" />
            <source>&amp;Help</source>
            <translation>&amp;Hilfe</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_desktop.py" line="288" />
            <source>User &amp;manual</source>
            <translation>Benutzer&amp;handbuch</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_desktop.py" line="291" />
            <source>The manual, at the part about what you are looking at</source>
            <translation>Das Handbuch, an der Stelle zu dem, was Sie gerade ansehen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_desktop.py" line="294" />
            <source>About &amp;Qt</source>
            <translation>Über &amp;Qt</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_desktop.py" line="345" />
            <source>Bus graph</source>
            <translation>Bus-Grafik</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_desktop.py" line="346" />
            <source>The devices of the bus and the links between their channels</source>
            <translation>Die Geräte des Busses und die Verbindungen zwischen ihren Kanälen</translation>
        </message>
        <message>
            <source>Opened capture {name}</source>
            <translation>Mitschnitt {name} geöffnet</translation>
        </message>
    </context>
    <context>
        <name>DeviceTree</name>
        <message>
            <location filename="../../pdcp_studio/app/tree_panel.py" line="32" />
            <source>Device / channel</source>
            <translation>Gerät / Kanal</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/tree_panel.py" line="32" />
            <source>Profile</source>
            <translation>Profil</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/tree_panel.py" line="74" />
            <source>missing</source>
            <translation>fehlt</translation>
        </message>
    </context>
    <context>
        <name>WindowExport</name>
        <message>
            <location filename="../../pdcp_studio/app/window_export.py" line="72" />
            <source>Export graph</source>
            <translation>Grafik exportieren</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_export.py" line="78" />
            <source>Exported {path}</source>
            <translation>{path} exportiert</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_export.py" line="80" />
            <source>Cannot export</source>
            <translation>Export nicht möglich</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_export.py" line="83" />
            <source>Fitting report</source>
            <translation>Anpassungsbericht</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_export.py" line="85" />
            <source>PDF (*.pdf)</source>
            <translation>PDF (*.pdf)</translation>
        </message>
    </context>
    <context>
        <name>WindowFiles</name>
        <message>
            <location filename="../../pdcp_studio/app/window_files.py" line="40" />
            <source>Cannot open</source>
            <translation>Öffnen nicht möglich</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_files.py" line="58" />
            <source>Opened {what} {v1}: {n_devices} devices, {n_links} links{note}</source>
            <translation>{what} {v1} geöffnet: {n_devices} Geräte, {n_links} Verbindungen{note}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_files.py" line="75" />
            <source>Opened stored configurations {name} in their own window</source>
            <translation>Gespeicherte Konfigurationen {name} in eigenem Fenster geöffnet</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_files.py" line="102" />
            <source>Connected to a prosthesis</source>
            <extracomment>``ask_leave_bus`` answers.</extracomment>
            <translation>Mit einer Prothese verbunden</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_files.py" line="103" />
            <source>another document</source>
            <translation>ein anderes Dokument</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_files.py" line="104" />
            <source>This window is connected to the prosthesis on {0}.
Opening {1} ends that connection.</source>
            <translation>Dieses Fenster ist mit der Prothese an {0} verbunden.
Das Öffnen von {1} beendet diese Verbindung.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_files.py" line="106" />
            <source>You can compare the file with the prosthesis instead, and stay connected.</source>
            <translation>Sie können die Datei stattdessen mit der Prothese vergleichen und verbunden bleiben.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_files.py" line="108" />
            <source>Compare with the prosthesis</source>
            <translation>Mit der Prothese vergleichen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_files.py" line="110" />
            <source>Disconnect and open</source>
            <translation>Trennen und öffnen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_files.py" line="127" />
            <source>Open</source>
            <translation>Öffnen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_files.py" line="140" />
            <source>Save as</source>
            <translation>Speichern unter</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_files.py" line="155" />
            <source>Cannot save</source>
            <translation>Speichern nicht möglich</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_files.py" line="159" />
            <source>Saved {path}</source>
            <translation>{path} gespeichert</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_files.py" line="176" />
            <source>Unsaved changes</source>
            <translation>Ungespeicherte Änderungen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_files.py" line="177" />
            <source>Save the changes to {title}?</source>
            <translation>Änderungen an {title} speichern?</translation>
        </message>
    </context>
    <context>
        <name>Effect</name>
        <message>
            <source>acknowledgement timeout</source>
            <translation>Bestätigungs-Zeitlimit</translation>
        </message>
        <message>
            <source>beacon interval</source>
            <translation>Beacon-Intervall</translation>
        </message>
        <message>
            <source>bind request timeout</source>
            <translation>Zeitlimit der Bindungsanfrage</translation>
        </message>
        <message>
            <source>{bits}-bit {kind}</source>
            <translation>{bits}-Bit {kind}</translation>
        </message>
        <message>
            <source>{what} {old} → {new}</source>
            <translation>{what} {old} → {new}</translation>
        </message>
        <message>
            <source>control mode</source>
            <translation>Regelungsart</translation>
        </message>
        <message>
            <source>data transfer</source>
            <translation>Datenübertragung</translation>
        </message>
        <message>
            <source>data type</source>
            <translation>Datentyp</translation>
        </message>
        <message>
            <source>desired inputs</source>
            <translation>gewünschte Eingänge</translation>
        </message>
        <message>
            <source>While the change is made, these parts are held still: {parts}.</source>
            <translation>Während der Änderung werden diese Teile stillgehalten: {parts}.</translation>
        </message>
        <message>
            <source>No part needs to be held still for this change.</source>
            <translation>Für diese Änderung muss kein Teil stillgehalten werden.</translation>
        </message>
        <message>
            <source>Link made: {link}</source>
            <translation>Verbindung hergestellt: {link}</translation>
        </message>
        <message>
            <source>Link removed: {link}</source>
            <translation>Verbindung entfernt: {link}</translation>
        </message>
        <message>
            <source>{n} ms</source>
            <translation>{n} ms</translation>
        </message>
        <message>
            <source>name</source>
            <translation>Name</translation>
        </message>
        <message>
            <source>no</source>
            <translation>nein</translation>
        </message>
        <message>
            <source>none</source>
            <translation>keine</translation>
        </message>
        <message>
            <source>Nothing changes on the prosthesis.</source>
            <translation>An der Prothese ändert sich nichts.</translation>
        </message>
        <message>
            <source>off</source>
            <translation>aus</translation>
        </message>
        <message>
            <source>on</source>
            <translation>an</translation>
        </message>
        <message>
            <source>{where}: {what}</source>
            <translation>{where}: {what}</translation>
        </message>
        <message>
            <source>Automatic set-up (autoconfigure): {old} → {new}.</source>
            <translation>Automatische Einrichtung (Autokonfiguration): {old} → {new}.</translation>
        </message>
        <message>
            <source>Turning automatic set-up off removes nothing: {links} stay as they are.</source>
            <translation>Das Ausschalten der automatischen Einrichtung entfernt nichts: {links} bleiben, wie sie sind.</translation>
        </message>
        <message>
            <source>{n} link</source>
            <translation>{n} Verbindung</translation>
        </message>
        <message>
            <source>  stays: {link}</source>
            <translation>  bleibt: {link}</translation>
        </message>
        <message>
            <source>This link stays but carries no data while data transfer is off at one of its ends: {link}</source>
            <translation>Diese Verbindung bleibt, überträgt aber keine Daten, solange die Datenübertragung an einem ihrer Enden aus ist: {link}</translation>
        </message>
        <message>
            <source>{n} links</source>
            <translation>{n} Verbindungen</translation>
        </message>
        <message>
            <source>  is made: {link}</source>
            <translation>  wird hergestellt: {link}</translation>
        </message>
        <message>
            <source>Automatic set-up is on: start-up links unconnected terminal channels.</source>
            <translation>Die automatische Einrichtung ist an: der Hochlauf verbindet unverbundene Endkanäle.</translation>
        </message>
        <message>
            <source>  comes back: {link}</source>
            <translation>  kommt zurück: {link}</translation>
        </message>
        <message>
            <source>  is removed: {link}</source>
            <translation>  wird entfernt: {link}</translation>
        </message>
        <message>
            <source>At the next power-on, start-up will change the links:</source>
            <translation>Beim nächsten Einschalten ändert der Hochlauf die Verbindungen:</translation>
        </message>
        <message>
            <source>Start-up undoes part of this change.</source>
            <translation>Der Hochlauf macht einen Teil dieser Änderung rückgängig.</translation>
        </message>
        <message>
            <source>No configuration is stored: start-up rebuilds the links from what the parts themselves remember.</source>
            <translation>Es ist keine Konfiguration gespeichert: der Hochlauf baut die Verbindungen aus dem auf, was die Teile selbst wissen.</translation>
        </message>
        <message>
            <source>This change is not stored: the next power-on undoes it. Store it as the prosthesis's configuration to keep it.</source>
            <translation>Diese Änderung ist nicht gespeichert: das nächste Einschalten macht sie rückgängig. Speichern Sie sie als Konfiguration der Prothese, um sie zu behalten.</translation>
        </message>
        <message>
            <source>Even stored, start-up's automatic set-up makes this again (autoconfigure is on): turn automatic set-up off to keep the change.</source>
            <translation>Auch gespeichert stellt die automatische Einrichtung des Hochlaufs dies wieder her (Autokonfiguration ist an): schalten Sie die automatische Einrichtung aus, um die Änderung zu behalten.</translation>
        </message>
        <message>
            <source>At the next power-on: nothing changes; start-up keeps these links.</source>
            <translation>Beim nächsten Einschalten: nichts ändert sich; der Hochlauf behält diese Verbindungen.</translation>
        </message>
        <message>
            <source>prescaler</source>
            <translation>Vorteiler</translation>
        </message>
        <message>
            <source>profile</source>
            <translation>Profil</translation>
        </message>
        <message>
            <source>required inputs</source>
            <translation>benötigte Eingänge</translation>
        </message>
        <message>
            <source>sole access</source>
            <translation>Alleinzugriff</translation>
        </message>
        <message>
            <source>  stored from now on: {link}</source>
            <translation>  ab jetzt gespeichert: {link}</translation>
        </message>
        <message>
            <source>Stored configuration: cleared (nothing stored).</source>
            <translation>Gespeicherte Konfiguration: gelöscht (nichts gespeichert).</translation>
        </message>
        <message>
            <source>  no longer stored: {link}</source>
            <translation>  nicht mehr gespeichert: {link}</translation>
        </message>
        <message>
            <source>Stored configuration: stored for the first time, {links}.</source>
            <translation>Gespeicherte Konfiguration: zum ersten Mal gespeichert, {links}.</translation>
        </message>
        <message>
            <source>Stored configuration: replaced; it will hold {links} ({added} added, {removed} removed).</source>
            <translation>Gespeicherte Konfiguration: ersetzt; sie enthält dann {links} ({added} hinzu, {removed} entfernt).</translation>
        </message>
        <message>
            <source>Stored configuration: unchanged.</source>
            <translation>Gespeicherte Konfiguration: unverändert.</translation>
        </message>
        <message>
            <source>terminal channel</source>
            <translation>Endkanal</translation>
        </message>
        <message>
            <source>terminal profile</source>
            <translation>Endprofil</translation>
        </message>
        <message>
            <source>yes</source>
            <translation>ja</translation>
        </message>
        <message>
            <source>position</source>
            <translation>Position</translation>
        </message>
        <message>
            <source>velocity</source>
            <translation>Geschwindigkeit</translation>
        </message>
        <message>
            <source>acceleration</source>
            <translation>Beschleunigung</translation>
        </message>
        <message>
            <source>other</source>
            <translation>andere</translation>
        </message>
        <message>
            <source>signed int</source>
            <translation>Ganzzahl mit Vorzeichen</translation>
        </message>
        <message>
            <source>unsigned int</source>
            <translation>Ganzzahl ohne Vorzeichen</translation>
        </message>
        <message>
            <source>float</source>
            <translation>Gleitkommazahl</translation>
        </message>
        <message>
            <source>boolean</source>
            <translation>Wahrheitswert</translation>
        </message>
    </context>
    <context>
        <name>LinkRefusal</name>
        <message>
            <source>that channel is not in the system</source>
            <translation>dieser Kanal ist nicht im System</translation>
        </message>
        <message>
            <source>a link starts at an output: {0} is an input</source>
            <translation>eine Verbindung beginnt an einem Ausgang: {0} ist ein Eingang</translation>
        </message>
        <message>
            <source>a link ends at an input: {0} is an output</source>
            <translation>eine Verbindung endet an einem Eingang: {0} ist ein Ausgang</translation>
        </message>
        <message>
            <source>a device must not send to itself (same-device link)</source>
            <translation>ein Gerät darf nicht an sich selbst senden (Verbindung im selben Gerät)</translation>
        </message>
        <message>
            <source>a channel of a missing device cannot be linked</source>
            <translation>ein Kanal eines fehlenden Geräts kann nicht verbunden werden</translation>
        </message>
        <message>
            <source>these channels are already linked</source>
            <translation>diese Kanäle sind bereits verbunden</translation>
        </message>
        <message>
            <source>input {0} already has a source ({1}); remove that link first</source>
            <translation>Eingang {0} hat bereits eine Quelle ({1}); entfernen Sie zuerst diese Verbindung</translation>
        </message>
        <message>
            <source>sole access: output {0} already feeds the sole-access input {1}</source>
            <translation>Alleinzugriff: Ausgang {0} speist bereits den Alleinzugriffs-Eingang {1}</translation>
        </message>
    </context>
    <context>
        <name>Commands</name>
        <message numerus="yes">
            <source>Apply the plan (%n step(s))</source>
            <translation>
                <numerusform>Plan ausführen (%n Schritt)</numerusform>
                <numerusform>Plan ausführen (%n Schritte)</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>Move %n part(s)</source>
            <translation>
                <numerusform>%n Teil verschieben</numerusform>
                <numerusform>%n Teile verschieben</numerusform>
            </translation>
        </message>
        <message>
            <source>Move {0}</source>
            <translation>{0} verschieben</translation>
        </message>
        <message>
            <source>{0}: {1} changed</source>
            <translation>{0}: {1} geändert</translation>
        </message>
        <message>
            <source>Link {0}</source>
            <translation>Verbinden: {0}</translation>
        </message>
        <message>
            <source>Remove link {0}</source>
            <translation>Verbindung entfernen: {0}</translation>
        </message>
        <message>
            <source>Remove {0} links</source>
            <translation>{0} Verbindungen entfernen</translation>
        </message>
    </context>
    <context>
        <name>RestoreRefusal</name>
        <message>
            <source>Fitting history entry {0} cannot be put back: it needs {1}, which is not on the bus. Nothing was written.</source>
            <translation>Eintrag {0} der Anpassungshistorie kann nicht wiederhergestellt werden: er braucht {1}, das nicht am Bus ist. Es wurde nichts geschrieben.</translation>
        </message>
        <message>
            <source>Fitting history entry {0} cannot be put back: it needs {1}, which are not on the bus. Nothing was written.</source>
            <translation>Eintrag {0} der Anpassungshistorie kann nicht wiederhergestellt werden: er braucht {1}, die nicht am Bus sind. Es wurde nichts geschrieben.</translation>
        </message>
        <message>
            <source>Plug the part in and try again, or use Replace a part to give its links to the part that took its place.</source>
            <translation>Stecken Sie das Teil ein und versuchen Sie es erneut, oder geben Sie mit „Ein Teil ersetzen“ seine Verbindungen an das Teil, das seinen Platz eingenommen hat.</translation>
        </message>
        <message>
            <source>Replace a part…</source>
            <translation>Ein Teil ersetzen…</translation>
        </message>
    </context>
    <context>
        <name>HistoryWords</name>
        <message>
            <source>(and {0} more)</source>
            <translation>(und {0} weitere)</translation>
        </message>
        <message>
            <source>This entry was recorded before PDCP Studio kept what a change does in words: it is shown as it was recorded.</source>
            <translation>Dieser Eintrag wurde aufgezeichnet, bevor PDCP Studio die Wirkung einer Änderung in Worten festhielt: er wird so gezeigt, wie er aufgezeichnet wurde.</translation>
        </message>
    </context>
    <context>
        <name>Fitting</name>
        <message>
            <location filename="../../pdcp_studio/app/fitting.py" line="77" />
            <source>Your name</source>
            <translation>Ihr Name</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/fitting.py" line="78" />
            <source>Changes to a prosthesis are recorded in the fitting history with the name of who made them.
Your name (asked once):</source>
            <translation>Änderungen an einer Prothese werden mit dem Namen der Person, die sie vorgenommen hat, in der Anpassungshistorie aufgezeichnet.
Ihr Name (wird einmal erfragt):</translation>
        </message>
    </context>
    <context>
        <name>HelpViewer</name>
        <message>
            <location filename="../../pdcp_studio/app/help_viewer.py" line="83" />
            <source>PDCP Studio — User manual</source>
            <translation>PDCP Studio — Benutzerhandbuch</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/help_viewer.py" line="87" />
            <source>User manual</source>
            <translation>Benutzerhandbuch</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/help_viewer.py" line="89" />
            <source>The user manual for prosthetists; F1 opens the part for the current view</source>
            <translation>Das Benutzerhandbuch für Orthopädietechniker; F1 öffnet den Teil zur aktuellen Ansicht</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/help_viewer.py" line="153" />
            <source>&lt;h3&gt;PDCP Studio&lt;/h3&gt;&lt;p&gt;See, configure and repair the PDCP bus inside a powered prosthesis.&lt;/p&gt;</source>
            <translation>&lt;h3&gt;PDCP Studio&lt;/h3&gt;&lt;p&gt;Den PDCP-Bus einer aktiven Prothese ansehen, einrichten und instand setzen.&lt;/p&gt;</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/help_viewer.py" line="156" />
            <source>&lt;p&gt;MIT License. Help → User manual (F1) explains every view.&lt;/p&gt;</source>
            <translation>&lt;p&gt;MIT-Lizenz. Hilfe → Benutzerhandbuch (F1) erklärt jede Ansicht.&lt;/p&gt;</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/help_viewer.py" line="158" />
            <source>About PDCP Studio</source>
            <translation>Über PDCP Studio</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/help_viewer.py" line="119" />
            <source>Picture not included in this installation: {name}</source>
            <translation>Bild in dieser Installation nicht enthalten: {name}</translation>
        </message>
    </context>
    <context>
        <name>HistoryPanel</name>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="42" />
            <source>Time (UTC)</source>
            <translation>Zeit (UTC)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="43" />
            <source>Action</source>
            <translation>Aktion</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="44" />
            <source>Outcome</source>
            <translation>Ergebnis</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="45" />
            <source>Operator</source>
            <translation>Bearbeiter</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="46" />
            <source>Patient</source>
            <translation>Patient</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="47" />
            <source>Links</source>
            <translation>Verbindungen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="48" />
            <source>Bus</source>
            <translation>Bus</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="79" />
            <source>applied, verified</source>
            <translation>angewendet, geprüft</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="81" />
            <source>applied</source>
            <translation>angewendet</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="85" />
            <source>rolled back</source>
            <translation>zurückgenommen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="87" />
            <source>failed</source>
            <translation>fehlgeschlagen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="96" />
            <source>Links after #{0}: {1}; after #{2}: {3}</source>
            <translation>Verbindungen nach #{0}: {1}; nach #{2}: {3}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="99" />
            <location filename="../../pdcp_studio/app/history_panel.py" line="101" />
            <source>  only after #{0}: {1}</source>
            <translation>  nur nach #{0}: {1}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="103" />
            <source>  the same links</source>
            <translation>  dieselben Verbindungen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="106" />
            <source>Stored configuration CRC after #{0}: {1}; after #{2}: {3}{4}</source>
            <translation>CRC der gespeicherten Konfiguration nach #{0}: {1}; nach #{2}: {3}{4}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="113" />
            <source> (the same)</source>
            <translation> (gleich)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="123" />
            <source>#{0} {1} — {2}</source>
            <translation>#{0} {1} — {2}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="125" />
            <source>Operator: {0}    Patient: {1}    Bus: {2}</source>
            <translation>Bearbeiter: {0}    Patient: {1}    Bus: {2}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="128" />
            <source>Outcome: {0}{1}</source>
            <translation>Ergebnis: {0}{1}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="131" />
            <source>Motion interlock: {0}</source>
            <translation>Bewegungssperre: {0}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="132" />
            <source>Stored configuration CRC: {0} → {1}</source>
            <translation>CRC der gespeicherten Konfiguration: {0} → {1}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="144" />
            <source>  parameter 0x{0:02X} of {1}/{2}/{3} channel {4} = {5}</source>
            <translation>  Parameter 0x{0:02X} von {1}/{2}/{3} Kanal {4} = {5}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="185" />
            <source>This prosthesis</source>
            <translation>Diese Prothese</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="186" />
            <source>All prostheses</source>
            <translation>Alle Prothesen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="189" />
            <source>Refresh</source>
            <translation>Aktualisieren</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="205" />
            <source>Restore on the prosthesis…</source>
            <translation>Auf der Prothese wiederherstellen…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="206" />
            <source>Put the connected prosthesis back as it was after this entry (previewed, confirmed)</source>
            <translation>Die verbundene Prothese in den Zustand nach diesem Eintrag zurückversetzen (mit Vorschau und Bestätigung)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="208" />
            <source>Fitting report…</source>
            <translation>Anpassungsbericht…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="213" />
            <source>Show:</source>
            <translation>Anzeigen:</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="218" />
            <source>Select two entries to see how they differ.</source>
            <translation>Zwei Einträge auswählen, um ihre Unterschiede zu sehen.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="247" />
            <source>{0} entries · chain intact</source>
            <translation>{0} Einträge · Kette intakt</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="250" />
            <source>The history was altered: {0}</source>
            <translation>Die Historie wurde verändert: {0}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="257" />
            <source>Cannot read the fitting history: {0}</source>
            <translation>Die Anpassungshistorie kann nicht gelesen werden: {0}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="311" />
            <source>Select an entry to see what it changed, or two to compare them.</source>
            <translation>Einen Eintrag auswählen, um zu sehen, was er geändert hat, oder zwei, um sie zu vergleichen.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="330" />
            <location filename="../../pdcp_studio/app/history_panel.py" line="338" />
            <source>Restore</source>
            <translation>Wiederherstellen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="330" />
            <source>connect to the prosthesis first</source>
            <translation>zuerst mit der Prothese verbinden</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="341" />
            <source>Restore history entry {0}</source>
            <translation>Historieneintrag {0} wiederherstellen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="349" />
            <source>Fitting report</source>
            <translation>Anpassungsbericht</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/history_panel.py" line="351" />
            <source>PDF (*.pdf)</source>
            <translation>PDF (*.pdf)</translation>
        </message>
        <message>
            <source>Ctrl+click a second entry to see how the two differ.</source>
            <translation>Mit Strg+Klick einen zweiten Eintrag wählen, um zu sehen, wie sich die beiden unterscheiden.</translation>
        </message>
        <message>
            <source>Technical detail</source>
            <translation>Technische Einzelheiten</translation>
        </message>
        <message>
            <source>Patient reference</source>
            <translation>Patientenreferenz</translation>
        </message>
        <message>
            <source>Show only the changes of the patients whose reference contains this text</source>
            <translation>Nur die Änderungen der Patienten zeigen, deren Referenz diesen Text enthält</translation>
        </message>
        <message>
            <source>Patient:</source>
            <translation>Patient:</translation>
        </message>
        <message>
            <source>Workstation: {0}</source>
            <translation>Arbeitsplatz: {0}</translation>
        </message>
        <message>
            <source>Imported from {0}, where it was entry #{1}</source>
            <translation>Übernommen aus {0}, dort Eintrag #{1}</translation>
        </message>
    </context>
    <context>
        <name>Inspector</name>
        <message>
            <source>Error</source>
            <translation>Fehler</translation>
        </message>
        <message>
            <source>Warning</source>
            <translation>Warnung</translation>
        </message>
        <message>
            <source>Note</source>
            <translation>Hinweis</translation>
        </message>
        <message>
            <source>Nothing to report: every check passed.</source>
            <translation>Nichts zu melden: alle Prüfungen bestanden.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="164" />
            <source>Live bus: an edit here is a pending change (one undo step); Write to prosthesis writes the pending changes in one transaction.</source>
            <extracomment>Device parameters (channel index 0) → Device attribute edited through them. A short message for the status bar (an edit refused, a link deleted). Editors and error labels of the current form by field name (tests drive them).</extracomment>
            <translation>Live-Bus: Eine Änderung hier ist eine vorgemerkte Änderung (ein Rückgängig-Schritt); „Auf die Prothese schreiben“ schreibt die vorgemerkten Änderungen in einem Vorgang.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="175" />
            <source>&lt;b&gt;{text}&lt;/b&gt;</source>
            <translation>&lt;b&gt;{text}&lt;/b&gt;</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="189" />
            <source>{title}&lt;br&gt;&lt;span style='color:#66707b; font-size:small'&gt;{meta}&lt;/span&gt;</source>
            <translation>{title}&lt;br&gt;&lt;span style='color:#66707b; font-size:small'&gt;{meta}&lt;/span&gt;</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="193" />
            <source>&lt;span style='color:#66707b; font-size:small'&gt;{meta}&lt;/span&gt;</source>
            <translation>&lt;span style='color:#66707b; font-size:small'&gt;{meta}&lt;/span&gt;</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="222" />
            <source>live: {0}</source>
            <translation>live: {0}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="224" />
            <source>System</source>
            <translation>System</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="224" />
            <source>{0} devices</source>
            <translation>{0} Geräte</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="225" />
            <source> ({0} missing)</source>
            <translation> ({0} fehlen)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="226" />
            <source>, {0} links · {1}</source>
            <translation>, {0} Verbindungen · {1}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="227" />
            <source>Select a device, channel or link on the graph or in the tree to see and edit its parameters.</source>
            <translation>Ein Gerät, einen Kanal oder eine Verbindung in der Grafik oder im Baum auswählen, um die Parameter zu sehen und zu bearbeiten.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="236" />
            <source>no</source>
            <translation>keine</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="266" />
            <source>a name for this device (not sent to it)</source>
            <translation>ein Name für dieses Gerät (wird nicht übertragen)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="303" />
            <source>not assigned</source>
            <translation>nicht zugewiesen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="333" />
            <source>the profile (bytes 2–3 of parameter 1)</source>
            <translation>das Profil (Bytes 2–3 von Parameter 1)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="343" />
            <source>enabled</source>
            <translation>aktiviert</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="414" />
            <source>sole access</source>
            <translation>alleiniger Zugriff</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="416" />
            <source>terminal</source>
            <translation>Endgerät</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="419" />
            <source>sole access is a property of input channels</source>
            <translation>alleiniger Zugriff ist eine Eigenschaft von Eingangskanälen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="420" />
            <source>terminal is a property of input channels</source>
            <translation>Endgerät ist eine Eigenschaft von Eingangskanälen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="478" />
            <source>choose a profile of the named tree or type one in hex</source>
            <translation>ein Profil aus dem Profilbaum wählen oder hexadezimal eingeben</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="526" />
            <source>Link</source>
            <translation>Verbindung</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="536" />
            <source>Delete link</source>
            <translation>Verbindung löschen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="545" />
            <source>Removed link {link}</source>
            <translation>Verbindung {link} entfernt</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/inspector.py" line="551" />
            <location filename="../../pdcp_studio/app/inspector.py" line="553" />
            <source>Refused: {reason}</source>
            <translation>Abgelehnt: {reason}</translation>
        </message>
        <message>
            <source>&lt;b&gt;Checks&lt;/b&gt; — no findings</source>
            <translation>&lt;b&gt;Prüfungen&lt;/b&gt; — keine Befunde</translation>
        </message>
        <message numerus="yes">
            <source>&lt;b&gt;Checks&lt;/b&gt; — %n finding(s)</source>
            <translation>
                <numerusform>&lt;b&gt;Prüfungen&lt;/b&gt; — %n Befund</numerusform>
                <numerusform>&lt;b&gt;Prüfungen&lt;/b&gt; — %n Befunde</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>%n device(s)</source>
            <translation>
                <numerusform>%n Gerät</numerusform>
                <numerusform>%n Geräte</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>%n link(s)</source>
            <translation>
                <numerusform>%n Verbindung</numerusform>
                <numerusform>%n Verbindungen</numerusform>
            </translation>
        </message>
    </context>
    <context>
        <name>Legend</name>
        <message>
            <location filename="../../pdcp_studio/app/graph/view.py" line="38" />
            <source>Sensor</source>
            <extracomment>Fit never magnifies beyond this (a three-card system should not look bloated). The legend's rows: (kind, colour, label). Kinds: "role" swatch, "ring" port, "line"/"dash"/"dashdot"/"dot" link.</extracomment>
            <translation>Sensor</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/view.py" line="39" />
            <source>Control</source>
            <translation>Steuerung</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/view.py" line="40" />
            <source>Terminal device</source>
            <translation>Endgerät</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/view.py" line="41" />
            <source>Missing</source>
            <translation>Fehlt</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/view.py" line="42" />
            <source>Required input unmet</source>
            <translation>Pflichteingang unverbunden</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/view.py" line="45" />
            <source>Link</source>
            <translation>Verbindung</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/view.py" line="46" />
            <source>Data flowing</source>
            <translation>Daten fließen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/view.py" line="47" />
            <source>End missing</source>
            <translation>Ende fehlt</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/view.py" line="48" />
            <source>Sole-access conflict</source>
            <translation>Konflikt beim alleinigen Zugriff</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/view.py" line="49" />
            <source>Plan adds</source>
            <translation>Plan fügt hinzu</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/view.py" line="50" />
            <source>Plan removes</source>
            <translation>Plan entfernt</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/view.py" line="53" />
            <source>Pending: to write</source>
            <translation>Vorgemerkt: zu schreiben</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/view.py" line="57" />
            <source>Pending: to remove from the prosthesis</source>
            <translation>Vorgemerkt: von der Prothese zu entfernen</translation>
        </message>
    </context>
    <context>
        <name>LiveController</name>
        <message>
            <location filename="../../pdcp_studio/app/live.py" line="107" />
            <source>Connecting to {url}…</source>
            <extracomment>The connection's states (``LiveController.state``). The connection's state changed (``OFFLINE``, ``CONNECTING``, ``LIVE``, ``DISCONNECTED``). A new session's bridge replaced the old one and its first snapshot is on screen. The bus as it is now (a snapshot merged into the document), after any bus event. Every bridge, when made (for docks that want frames or values). The URL being connected to (while ``state`` is ``CONNECTING``). The last connection's URL (shown while ``DISCONNECTED``). A callable given each output ref that sent data (the scene's ``note_data``).</extracomment>
            <translation>Verbindung mit {url} wird hergestellt…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/live.py" line="139" />
            <source>Bus: {msg}</source>
            <translation>Bus: {msg}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/live.py" line="159" />
            <source>Live: {url} — {devices}, {links}</source>
            <translation>Live: {url} — {devices}, {links}</translation>
        </message>
        <message numerus="yes">
            <source>%n device(s)</source>
            <translation>
                <numerusform>%n Gerät</numerusform>
                <numerusform>%n Geräte</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>%n link(s)</source>
            <translation>
                <numerusform>%n Verbindung</numerusform>
                <numerusform>%n Verbindungen</numerusform>
            </translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/live.py" line="189" />
            <source>live on {0}, connecting to {1}…</source>
            <translation>live an {0}, Verbindung mit {1} wird hergestellt…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/live.py" line="191" />
            <source>connecting to {0}…</source>
            <translation>Verbindung mit {0} wird hergestellt…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/live.py" line="193" />
            <source>live on {0}</source>
            <translation>live an {0}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/live.py" line="195" />
            <source>disconnected from {0}</source>
            <translation>von {0} getrennt</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/live.py" line="196" />
            <source>offline</source>
            <translation>offline</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/live.py" line="234" />
            <source>Device {key} joined the bus</source>
            <translation>Gerät {key} ist dem Bus beigetreten</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/live.py" line="241" />
            <source>{v0} left the bus</source>
            <translation>{v0} hat den Bus verlassen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/live.py" line="248" />
            <source>The bus applied {mode}</source>
            <translation>Der Bus hat {mode} ausgeführt</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/live.py" line="248" />
            <source>The prosthesis changed its links ({why}): {added} made, {removed} removed — see Bus events</source>
            <translation>Die Prothese hat ihre Verbindungen geändert ({why}): {added} hergestellt, {removed} entfernt — siehe Busereignisse</translation>
        </message>
        <message>
            <source>{part} joined the bus</source>
            <translation>{part} ist dem Bus beigetreten</translation>
        </message>
        <message>
            <source>{part} left the bus</source>
            <translation>{part} hat den Bus verlassen</translation>
        </message>
    </context>
    <context>
        <name>MainWindow</name>
        <message>
            <source>&amp;Go to device…</source>
            <translation>&amp;Gehe zu Gerät…</translation>
        </message>
        <message>
            <source>Find a device by name and show it on the graph</source>
            <translation>Ein Gerät über seinen Namen finden und im Graphen zeigen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/main_window.py" line="72" />
            <source>PDCP Studio</source>
            <extracomment>The first system is on screen and laid out (a file, a bus, or the offline fallback).</extracomment>
            <translation>PDCP Studio</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/main_window.py" line="112" />
            <source>Devices</source>
            <translation>Geräte</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/main_window.py" line="114" />
            <source>Inspector</source>
            <translation>Inspektor</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/main_window.py" line="116" />
            <source>Plan</source>
            <translation>Plan</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/main_window.py" line="131" />
            <location filename="../../pdcp_studio/app/main_window.py" line="193" />
            <source>Offline</source>
            <translation>Offline</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/main_window.py" line="170" />
            <source>{v0}{v1}[*] — PDCP Studio</source>
            <translation>{v0}{v1}[*] — PDCP Studio</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/main_window.py" line="175" />
            <source>{title}[*]{where} — PDCP Studio</source>
            <translation>{title}[*]{where} — PDCP Studio</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/main_window.py" line="185" />
            <source>● Live on {0} — connecting to {1}…</source>
            <translation>● Live an {0} — Verbindung mit {1} wird hergestellt…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/main_window.py" line="186" />
            <source>Connecting to {1}…</source>
            <translation>Verbindung mit {1} wird hergestellt…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/main_window.py" line="189" />
            <source>● Live on {0}</source>
            <translation>● Live an {0}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/main_window.py" line="191" />
            <source>Disconnected from {0}</source>
            <translation>Von {0} getrennt</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/main_window.py" line="199" />
            <source>The prosthesis this window is connected to (the document is the project, the prosthesis the target)</source>
            <translation>Die Prothese, mit der dieses Fenster verbunden ist (das Dokument ist das Projekt, die Prothese das Ziel)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/main_window.py" line="262" />
            <source>Cannot connect</source>
            <translation>Verbinden nicht möglich</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/main_window.py" line="280" />
            <source>Offline: {why}. Showing the shipped {OFFLINE_SYSTEM}.</source>
            <translation>Offline: {why}. Angezeigt wird das mitgelieferte {OFFLINE_SYSTEM}.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/main_window.py" line="326" />
            <source>About PDCP Studio</source>
            <translation>Über PDCP Studio</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/main_window.py" line="327" />
            <source>PDCP Studio {version__}
See and configure the PDCP bus inside a powered prosthesis.</source>
            <translation>PDCP Studio {version__}
Den PDCP-Bus einer aktiven Prothese ansehen und einrichten.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_transactions.py" line="34" />
            <location filename="../../pdcp_studio/app/window_transactions.py" line="146" />
            <source>Pending changes</source>
            <translation>Vorgemerkte Änderungen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_transactions.py" line="39" />
            <source>Fitting history</source>
            <translation>Anpassungshistorie</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_transactions.py" line="50" />
            <source>&amp;Write to prosthesis…</source>
            <translation>Auf die Prothese &amp;schreiben…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_transactions.py" line="53" />
            <source>Show the pending changes' difference and write them in one transaction</source>
            <translation>Den Unterschied der vorgemerkten Änderungen zeigen und sie in einem Vorgang schreiben</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_transactions.py" line="60" />
            <source>&amp;Discard pending changes</source>
            <translation>Vorgemerkte Änderungen &amp;verwerfen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_transactions.py" line="66" />
            <source>Fitting &amp;history</source>
            <translation>Anpassungs&amp;historie</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_transactions.py" line="112" />
            <source>Links as on the prosthesis</source>
            <translation>Verbindungen wie auf der Prothese</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_transactions.py" line="207" />
            <source>Cannot write the report</source>
            <translation>Der Bericht kann nicht geschrieben werden</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_transactions.py" line="209" />
            <source>Wrote the fitting report {0}</source>
            <translation>Anpassungsbericht {0} geschrieben</translation>
        </message>
        <message numerus="yes">
            <source>Discard %n pending change(s)</source>
            <translation>
                <numerusform>%n vorgemerkte Änderung verwerfen</numerusform>
                <numerusform>%n vorgemerkte Änderungen verwerfen</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>Discarded %n pending change(s): the project is as the prosthesis (Undo brings them back)</source>
            <translation>
                <numerusform>%n vorgemerkte Änderung verworfen: Das Projekt entspricht der Prothese (Rückgängig holt sie zurück)</numerusform>
                <numerusform>%n vorgemerkte Änderungen verworfen: Das Projekt entspricht der Prothese (Rückgängig holt sie zurück)</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>%n change(s) not written to the prosthesis. Leave it without them?
(Write to prosthesis writes them; the document keeps them either way.)</source>
            <translation>
                <numerusform>%n Änderung wurde nicht auf die Prothese geschrieben. Ohne sie trennen?
(„Auf die Prothese schreiben“ schreibt sie; das Dokument behält sie in jedem Fall.)</numerusform>
                <numerusform>%n Änderungen wurden nicht auf die Prothese geschrieben. Ohne sie trennen?
(„Auf die Prothese schreiben“ schreibt sie; das Dokument behält sie in jedem Fall.)</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>%n change(s) not written to the prosthesis on {url} yet.</source>
            <translation>
                <numerusform>%n Änderung ist noch nicht auf die Prothese an {url} geschrieben.</numerusform>
                <numerusform>%n Änderungen sind noch nicht auf die Prothese an {url} geschrieben.</numerusform>
            </translation>
        </message>
        <message>
            <source>Write them now (you see the difference and confirm it), or quit and discard them: the prosthesis stays as it is.</source>
            <translation>Schreiben Sie sie jetzt (Sie sehen den Unterschied und bestätigen ihn), oder beenden Sie und verwerfen Sie sie: Die Prothese bleibt, wie sie ist.</translation>
        </message>
        <message>
            <source>Write to prosthesis…</source>
            <translation>Auf die Prothese schreiben…</translation>
        </message>
        <message>
            <source>Discard and quit</source>
            <translation>Verwerfen und beenden</translation>
        </message>
    </context>
    <context>
        <name>WindowActions</name>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="37" />
            <source>&amp;Open…</source>
            <translation>Ö&amp;ffnen…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="40" />
            <source>Open a system file (.json) or a configuration (.pdcfg)</source>
            <translation>Eine Systemdatei (.json) oder eine Konfiguration (.pdcfg) öffnen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="42" />
            <source>&amp;Save</source>
            <translation>&amp;Speichern</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="43" />
            <source>Save &amp;As…</source>
            <translation>Speichern &amp;unter…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="44" />
            <source>Export graph as &amp;PNG…</source>
            <translation>Grafik als &amp;PNG exportieren…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="46" />
            <source>Export graph as S&amp;VG…</source>
            <translation>Grafik als S&amp;VG exportieren…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="48" />
            <source>Fitting &amp;report (PDF)…</source>
            <translation>Anpassungs&amp;bericht (PDF)…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="49" />
            <source>&amp;Quit</source>
            <translation>&amp;Beenden</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="50" />
            <source>&amp;Undo</source>
            <translation>&amp;Rückgängig</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="52" />
            <source>&amp;Redo</source>
            <translation>&amp;Wiederholen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="54" />
            <source>&amp;Delete link</source>
            <translation>Verbindung &amp;löschen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="55" />
            <source>Remove the selected links</source>
            <translation>Die ausgewählten Verbindungen entfernen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="56" />
            <source>&amp;Fit to window</source>
            <translation>An &amp;Fenster anpassen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="58" />
            <source>Zoom &amp;in</source>
            <translation>Ver&amp;größern</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="61" />
            <source>Zoom &amp;out</source>
            <translation>Ver&amp;kleinern</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="64" />
            <source>Show &amp;legend</source>
            <translation>&amp;Legende anzeigen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="69" />
            <source>&amp;Arrange in layers</source>
            <translation>In Ebenen &amp;anordnen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="70" />
            <source>Lay the cards out again: sensors → control → terminal devices (one undo step)</source>
            <translation>Die Karten neu anordnen: Sensoren → Steuerung → Endgeräte (ein Rückgängig-Schritt)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="77" />
            <source>&amp;Connect…</source>
            <translation>&amp;Verbinden…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="79" />
            <source>Connect to a simulated prosthesis or a CAN bus</source>
            <translation>Mit einer simulierten Prothese oder einem CAN-Bus verbinden</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="82" />
            <source>Open the &amp;simulated prosthesis</source>
            <translation>&amp;Simulierte Prothese öffnen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="84" />
            <source>&amp;Disconnect</source>
            <translation>&amp;Trennen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="85" />
            <source>&amp;Scan the bus</source>
            <translation>Bus &amp;abfragen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="87" />
            <source>&amp;Read the stored configuration</source>
            <translation>Gespeicherte Konfiguration &amp;lesen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="88" />
            <source>Read the arbitrator's stored configuration; plans that take a configuration (Find replacements, Start-up) then use it</source>
            <translation>Die gespeicherte Konfiguration des Arbiters lesen; Pläne mit Konfiguration (Ersatz finden, Hochlauf) verwenden sie dann</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="91" />
            <source>Ca&amp;ncel bus work</source>
            <translation>Bus-Arbeit a&amp;bbrechen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="94" />
            <source>Cancel what the bus is doing for you (scan, apply…)</source>
            <translation>Abbrechen, was der Bus gerade für Sie tut (Abfragen, Anwenden…)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="96" />
            <source>Co&amp;mpare configurations…</source>
            <translation>Konfigurationen &amp;vergleichen…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="97" />
            <source>&amp;Write configuration to the arbitrator…</source>
            <translation>Konfiguration in den Arbiter &amp;schreiben…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="99" />
            <source>&amp;Profile tree…</source>
            <translation>&amp;Profilbaum…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="100" />
            <source>&amp;About PDCP Studio</source>
            <translation>Ü&amp;ber PDCP Studio</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="104" />
            <source>&amp;File</source>
            <translation>&amp;Datei</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="112" />
            <source>&amp;Edit</source>
            <translation>&amp;Bearbeiten</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="119" />
            <source>&amp;View</source>
            <translation>&amp;Ansicht</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="126" />
            <source>&amp;Plan</source>
            <translation>&amp;Plan</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="129" />
            <source>&amp;Bus</source>
            <translation>B&amp;us</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_menus.py" line="136" />
            <source>&amp;Help</source>
            <translation>&amp;Hilfe</translation>
        </message>
        <message>
            <source>Export graph as P&amp;DF…</source>
            <translation>Grafik als P&amp;DF exportieren…</translation>
        </message>
    </context>
    <context>
        <name>MonitorDock</name>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="75" />
            <source>(any)</source>
            <extracomment>A visible table takes new rows at most this often: painting it costs the GUI thread milliseconds, and a saturated bus brings a batch every few milliseconds. Rows an opened capture sends to the table at a time (the first ones at once).</extracomment>
            <translation>(alle)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="78" />
            <source>Time</source>
            <translation>Zeit</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="78" />
            <source>ID</source>
            <translation>ID</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="79" />
            <source>Node</source>
            <translation>Knoten</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="80" />
            <source>Function</source>
            <translation>Funktion</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="81" />
            <source>Data</source>
            <translation>Daten</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="81" />
            <source>Decoded</source>
            <translation>Dekodiert</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="262" />
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="602" />
            <source>Bus monitor</source>
            <translation>Bus-Monitor</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="309" />
            <source>Filter text or hex…</source>
            <extracomment>While a capture is open the table shows it, apart from the live frames, which keep being recorded in ``live_rows`` and come back with ``show_live()``.</extracomment>
            <translation>Text oder Hex filtern…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="317" />
            <source>any node</source>
            <translation>jeder Knoten</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="319" />
            <source>Pause</source>
            <translation>Anhalten</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="320" />
            <source>Autoscroll</source>
            <translation>Mitlaufen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="322" />
            <source>Clear</source>
            <translation>Leeren</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="323" />
            <source>Save…</source>
            <translation>Speichern…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="324" />
            <source>Open…</source>
            <translation>Öffnen…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="325" />
            <source>Show a capture file (python-can log formats)</source>
            <translation>Eine Mitschnittdatei anzeigen (python-can-Protokollformate)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="326" />
            <source>Back to live</source>
            <translation>Zurück zu live</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="327" />
            <source>Close the capture and show the live frames again</source>
            <translation>Den Mitschnitt schließen und wieder die Live-Nachrichten zeigen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="329" />
            <source>Stop loading</source>
            <translation>Laden anhalten</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="331" />
            <source>0 frames</source>
            <translation>0 Nachrichten</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="493" />
            <source>{shown} of {total} frames</source>
            <translation>{shown} von {total} Nachrichten</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="495" />
            <source>{total} frames</source>
            <translation>{total} Nachrichten</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="502" />
            <source>Save frames</source>
            <translation>Nachrichten speichern</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="503" />
            <source>python-can logs (*.asc *.blf *.log *.csv *.trc);;Plain text (*.txt)</source>
            <translation>python-can-Protokolle (*.asc *.blf *.log *.csv *.trc);;Reiner Text (*.txt)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="509" />
            <source>Open capture</source>
            <translation>Mitschnitt öffnen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="510" />
            <source>python-can logs (*.asc *.blf *.log *.csv *.trc *.db *.gz);;All files (*)</source>
            <translation>python-can-Protokolle (*.asc *.blf *.log *.csv *.trc *.db *.gz);;Alle Dateien (*)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="616" />
            <source>Bus monitor — capture %1</source>
            <translation>Bus-Monitor — Mitschnitt %1</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="628" />
            <source>%1 frames read</source>
            <translation>%1 Nachrichten gelesen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="636" />
            <source>first %1 of %2 frames</source>
            <translation>erste %1 von %2 Nachrichten</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="647" />
            <source>Reading {load_path}: {message}</source>
            <translation>{load_path} lesen: {message}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/monitor_dock.py" line="657" />
            <source>Saving {save_path}: {message}</source>
            <translation>{save_path} speichern: {message}</translation>
        </message>
        <message>
            <source>Record…</source>
            <translation>Aufzeichnen…</translation>
        </message>
        <message>
            <source>Write every live frame to a capture file (the table keeps only the newest ones)</source>
            <translation>Jeden Live-Frame in eine Aufzeichnungsdatei schreiben (die Tabelle behält nur die neuesten)</translation>
        </message>
        <message>
            <source>Record live frames</source>
            <translation>Live-Frames aufzeichnen</translation>
        </message>
        <message>
            <source>python-can logs (*.blf *.asc *.log *.csv *.trc)</source>
            <translation>python-can-Aufzeichnungen (*.blf *.asc *.log *.csv *.trc)</translation>
        </message>
        <message>
            <source>Recording {path}: {message}</source>
            <translation>Aufzeichnung {path}: {message}</translation>
        </message>
        <message>
            <source>Recording</source>
            <translation>Zeichnet auf</translation>
        </message>
        <message>
            <source> · recording to {name}</source>
            <translation> · Aufzeichnung in {name}</translation>
        </message>
        <message>
            <source>Add marker</source>
            <translation>Markierung setzen</translation>
        </message>
        <message>
            <source>Any node</source>
            <translation>Jeder Knoten</translation>
        </message>
        <message>
            <source>Broadcast</source>
            <translation>Rundruf</translation>
        </message>
        <message>
            <source>Filter text, ID or data…</source>
            <translation>Text, ID oder Daten filtern…</translation>
        </message>
        <message>
            <source>Find text or ID…</source>
            <translation>Text oder ID suchen…</translation>
        </message>
        <message>
            <source>Find the next frame</source>
            <translation>Nächsten Frame suchen</translation>
        </message>
        <message>
            <source>Find the previous frame</source>
            <translation>Vorherigen Frame suchen</translation>
        </message>
        <message>
            <source>Freeze the table; frames are still recorded and counted</source>
            <translation>Tabelle anhalten; Frames werden weiter aufgezeichnet und gezählt</translation>
        </message>
        <message>
            <source>Go to a marker (times since a marker count from it)</source>
            <translation>Zu einer Markierung springen (Zeiten seit Markierung zählen ab ihr)</translation>
        </message>
        <message>
            <source>How the Time column counts</source>
            <translation>Wie die Zeitspalte zählt</translation>
        </message>
        <message>
            <source>Mark the selected frame, or the newest one</source>
            <translation>Den gewählten oder den neuesten Frame markieren</translation>
        </message>
        <message>
            <source>No markers</source>
            <translation>Keine Markierungen</translation>
        </message>
        <message>
            <source>Per identifier: frames counted, mean period, last period, last data and what it means. Double-click to show only that identifier.</source>
            <translation>Je Kennung: gezählte Frames, mittlere Periode, letzte Periode, letzte Daten und ihre Bedeutung. Doppelklick zeigt nur diese Kennung.</translation>
        </message>
        <message>
            <source>Show the frames of one node only</source>
            <translation>Nur die Frames eines Knotens zeigen</translation>
        </message>
        <message>
            <source>{device} output {index}</source>
            <translation>{device} Ausgang {index}</translation>
        </message>
        <message>
            <source>{name} (node {node})</source>
            <translation>{name} (Knoten {node})</translation>
        </message>
        <message>
            <source>Node {node}</source>
            <translation>Knoten {node}</translation>
        </message>
        <message>
            <source>Marker {n}</source>
            <translation>Markierung {n}</translation>
        </message>
        <message>
            <source>Filtering…</source>
            <translation>Filtern…</translation>
        </message>
        <message>
            <source>%1 frames</source>
            <translation>%1 Frames</translation>
        </message>
        <message>
            <source>frames</source>
            <translation>Frames</translation>
        </message>
        <message>
            <source>Kind</source>
            <translation>Art</translation>
        </message>
        <message>
            <source>DLC</source>
            <translation>DLC</translation>
        </message>
        <message>
            <source>not read</source>
            <translation>nicht gelesen</translation>
        </message>
        <message>
            <source>{path}: a pipe or a device, not a capture file (the app opens files; read a pipe with pdcp-studio monitor --replay)</source>
            <translation>{path}: eine Pipe oder ein Gerät, keine Mitschnittdatei (die App öffnet Dateien; eine Pipe liest pdcp-studio monitor --replay)</translation>
        </message>
        <message>
            <source>Captures ({globs})</source>
            <translation>Mitschnitte ({globs})</translation>
        </message>
        <message>
            <source>ASAM MDF4 (*.mf4)</source>
            <translation>ASAM MDF4 (*.mf4)</translation>
        </message>
        <message>
            <source>ASAM MDF4, needs python-can's mf4 extra, not installed (*.mf4)</source>
            <translation>ASAM MDF4, braucht das mf4-Extra von python-can, nicht installiert (*.mf4)</translation>
        </message>
        <message>
            <source>All files (*)</source>
            <translation>Alle Dateien (*)</translation>
        </message>
        <message>
            <source>node map from {name}</source>
            <translation>Knotenzuordnung aus {name}</translation>
        </message>
        <message>
            <source>node map from the capture's set-up: {devices}, {channels}</source>
            <translation>Knotenzuordnung aus der Einrichtung im Mitschnitt: {devices}, {channels}</translation>
        </message>
        <message>
            <source>node map inferred from traffic: {devices}, {channels}</source>
            <translation>Knotenzuordnung aus dem Verkehr erschlossen: {devices}, {channels}</translation>
        </message>
        <message>
            <source>no node map (no set-up in the capture, nothing to infer from)</source>
            <translation>keine Knotenzuordnung (keine Einrichtung im Mitschnitt, nichts zu erschließen)</translation>
        </message>
        <message>
            <source>Empty capture: no frames</source>
            <translation>Leerer Mitschnitt: keine Nachrichten</translation>
        </message>
        <message>
            <source>Not PDCP: shown as plain CAN frames</source>
            <translation>Kein PDCP: als einfache CAN-Nachrichten gezeigt</translation>
        </message>
        <message>
            <source>Reading…</source>
            <translation>Wird gelesen…</translation>
        </message>
        <message>
            <source>PDCP capture</source>
            <translation>PDCP-Mitschnitt</translation>
        </message>
        <message>
            <source>Cut short: {damage} — the {frames} frames before it are shown</source>
            <translation>Abgebrochen: {damage} — die {frames} Nachrichten davor werden gezeigt</translation>
        </message>
        <message>
            <source>Stopped: the first {frames} frames are shown</source>
            <translation>Angehalten: die ersten {frames} Nachrichten werden gezeigt</translation>
        </message>
        <message>
            <source>Stopped before the first frames were read</source>
            <translation>Angehalten, bevor die ersten Nachrichten gelesen waren</translation>
        </message>
        <message>
            <source>This capture could not be read:
{message}</source>
            <translation>Dieser Mitschnitt konnte nicht gelesen werden:
{message}</translation>
        </message>
        <message numerus="yes">
            <source>%n device(s)</source>
            <translation>
                <numerusform>%n Gerät</numerusform>
                <numerusform>%n Geräte</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>%n channel(s)</source>
            <translation>
                <numerusform>%n Kanal</numerusform>
                <numerusform>%n Kanäle</numerusform>
            </translation>
        </message>
    </context>
    <context>
        <name>Pending</name>
        <message>
            <location filename="../../pdcp_studio/app/pending.py" line="84" />
            <source>on</source>
            <extracomment>Channel fields that can be staged on a live bus: field → catalog parameter ID. Device fields that can be staged on a live bus: field → catalog parameter ID. The action a written set of pending changes is recorded as.</extracomment>
            <translation>an</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/pending.py" line="84" />
            <source>off</source>
            <translation>aus</translation>
        </message>
    </context>
    <context>
        <name>PendingPanel</name>
        <message>
            <location filename="../../pdcp_studio/app/pending_panel.py" line="54" />
            <source>free text, as your clinic chooses</source>
            <extracomment>The user asked to write the pending changes (the window runs the transaction). The user asked to drop the pending changes. The patient reference was edited (text). The list was computed again.</extracomment>
            <translation>freier Text, wie Ihre Klinik es festlegt</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/pending_panel.py" line="55" />
            <source>The patient reference belongs to the prosthesis: it is recorded with every change and printed on the fitting report</source>
            <translation>Die Patientenreferenz gehört zur Prothese: Sie wird mit jeder Änderung aufgezeichnet und auf den Anpassungsbericht gedruckt</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/pending_panel.py" line="63" />
            <source>Change</source>
            <translation>Änderung</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/pending_panel.py" line="63" />
            <source>What</source>
            <translation>Was</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/pending_panel.py" line="63" />
            <source>Why</source>
            <translation>Warum</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/pending_panel.py" line="73" />
            <source>Write to prosthesis…</source>
            <translation>Auf die Prothese schreiben…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/pending_panel.py" line="74" />
            <source>Show the difference, then write every pending change in one transaction</source>
            <translation>Den Unterschied zeigen und dann alle vorgemerkten Änderungen in einem Vorgang schreiben</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/pending_panel.py" line="76" />
            <source>Discard pending changes</source>
            <translation>Vorgemerkte Änderungen verwerfen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/pending_panel.py" line="81" />
            <source>Patient reference:</source>
            <translation>Patientenreferenz:</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/pending_panel.py" line="119" />
            <source>+ link</source>
            <translation>+ Verbindung</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/pending_panel.py" line="119" />
            <source>− link</source>
            <translation>− Verbindung</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/pending_panel.py" line="120" />
            <source>parameter</source>
            <translation>Parameter</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/pending_panel.py" line="130" />
            <source>Offline: edits change the document only. Connect to a prosthesis to write to it.</source>
            <translation>Offline: Änderungen betreffen nur das Dokument. Mit einer Prothese verbinden, um auf sie zu schreiben.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/pending_panel.py" line="133" />
            <source>No pending changes: the project and the prosthesis on {0} agree.</source>
            <translation>Keine vorgemerkten Änderungen: Projekt und Prothese an {0} stimmen überein.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/pending_panel.py" line="145" />
            <source>Operator: {0}</source>
            <translation>Bearbeiter: {0}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/pending_panel.py" line="146" />
            <source>Operator: (asked at the first write)</source>
            <translation>Bearbeiter: (wird beim ersten Schreiben erfragt)</translation>
        </message>
        <message>
            <source>&lt;b&gt;{0}&lt;/b&gt; for the prosthesis on {1}: edits are staged here and reach the prosthesis only with Write to prosthesis.</source>
            <translation>&lt;b&gt;{0}&lt;/b&gt; für die Prothese an {1}: Änderungen werden hier gesammelt und erreichen die Prothese erst mit „Auf die Prothese schreiben“.</translation>
        </message>
        <message numerus="yes">
            <source>%n pending change(s)</source>
            <translation>
                <numerusform>%n vorgemerkte Änderung</numerusform>
                <numerusform>%n vorgemerkte Änderungen</numerusform>
            </translation>
        </message>
        <message>
            <source>linked by hand</source>
            <translation>von Hand verbunden</translation>
        </message>
        <message>
            <source>removed by hand</source>
            <translation>von Hand entfernt</translation>
        </message>
        <message>
            <source>as on the prosthesis</source>
            <translation>wie an der Prothese</translation>
        </message>
    </context>
    <context>
        <name>PlanPanel</name>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="40" />
            <source>Autoconfigure</source>
            <extracomment>The operations offered, in menu order: (engine mode, menu text).</extracomment>
            <translation>Automatisch konfigurieren</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="41" />
            <source>Find replacements</source>
            <translation>Ersatz finden</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="42" />
            <source>Start-up</source>
            <translation>Hochlauf</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="43" />
            <source>Enforce sole access</source>
            <translation>Alleinigen Zugriff durchsetzen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="65" />
            <source>Preview what {v0} would change</source>
            <extracomment>A plan was applied: one undo step (on a live bus a staged change).</extracomment>
            <translation>Vorschau, was {v0} ändern würde</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="72" />
            <location filename="../../pdcp_studio/app/plan_panel.py" line="170" />
            <source>No plan previewed. Choose an operation to see what it would change before anything changes.</source>
            <translation>Kein Plan in der Vorschau. Einen Vorgang wählen, um zu sehen, was er ändern würde, bevor sich etwas ändert.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="79" />
            <source>Action</source>
            <translation>Aktion</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="79" />
            <source>Output → input</source>
            <translation>Ausgang → Eingang</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="79" />
            <source>Rule</source>
            <translation>Regel</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="79" />
            <source>Similarity</source>
            <translation>Ähnlichkeit</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="92" />
            <source>Discard</source>
            <translation>Verwerfen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="93" />
            <location filename="../../pdcp_studio/app/plan_panel.py" line="150" />
            <source>Apply</source>
            <translation>Anwenden</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="123" />
            <source>&lt;span style='color:#b91c1c'&gt;Cannot plan: {err}&lt;/span&gt;</source>
            <translation>&lt;span style='color:#b91c1c'&gt;Planen nicht möglich: {err}&lt;/span&gt;</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="149" />
            <source>Stage for the prosthesis</source>
            <translation>Für die Prothese vormerken</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="152" />
            <source>Add the plan to the pending changes; Write to prosthesis writes them in one transaction</source>
            <translation>Den Plan zu den vorgemerkten Änderungen hinzufügen; „Auf die Prothese schreiben“ schreibt sie in einem Vorgang</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="153" />
            <source>Apply the plan (one undo step)</source>
            <translation>Den Plan anwenden (ein Rückgängig-Schritt)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="174" />
            <source>&lt;b&gt;{0}&lt;/b&gt;: add {1}, remove {2} ({3} links before, {4} after)</source>
            <translation>&lt;b&gt;{0}&lt;/b&gt;: {1} hinzufügen, {2} entfernen ({3} Verbindungen vorher, {4} nachher)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="236" />
            <source>Plan discarded: nothing changed</source>
            <translation>Plan verworfen: nichts geändert</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="247" />
            <source>Staged {0}: {1} to add, {2} to remove — Write to prosthesis writes them (Undo unstages)</source>
            <translation>{0} vorgemerkt: {1} hinzuzufügen, {2} zu entfernen — „Auf die Prothese schreiben“ schreibt sie (Rückgängig nimmt es zurück)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/plan_panel.py" line="252" />
            <source>Applied {mode}: {n_added} added, {n_removed} removed (Undo reverts it)</source>
            <translation>{mode} angewendet: {n_added} hinzugefügt, {n_removed} entfernt (Rückgängig macht es ungeschehen)</translation>
        </message>
        <message>
            <source>Change</source>
            <translation>Änderung</translation>
        </message>
        <message>
            <source>Link</source>
            <translation>Verbindung</translation>
        </message>
        <message>
            <source>Why</source>
            <translation>Warum</translation>
        </message>
        <message>
            <source>How similar</source>
            <translation>Wie ähnlich</translation>
        </message>
        <message>
            <source>Select a row for the engineer's detail: the engine's reason, profile codes and the similarity score</source>
            <translation>Wählen Sie eine Zeile für die technischen Einzelheiten: Begründung der Planung, Profilcodes und Ähnlichkeitswert</translation>
        </message>
        <message>
            <source> (missing)</source>
            <translation> (fehlt)</translation>
        </message>
        <message>
            <source>Stored set-up used: {reason}</source>
            <translation>Verwendete gespeicherte Einrichtung: {reason}</translation>
        </message>
        <message>
            <source>Nothing to change.</source>
            <translation>Nichts zu ändern.</translation>
        </message>
        <message>
            <source>Add</source>
            <translation>Hinzufügen</translation>
        </message>
        <message>
            <source>Remove</source>
            <translation>Entfernen</translation>
        </message>
        <message>
            <source>Not done</source>
            <translation>Nicht ausgeführt</translation>
        </message>
        <message>
            <source>Note</source>
            <translation>Hinweis</translation>
        </message>
        <message>
            <source> ({channel} is missing)</source>
            <translation> ({channel} fehlt)</translation>
        </message>
    </context>
    <context>
        <name>WindowPolicy</name>
        <message>
            <location filename="../../pdcp_studio/app/window_policy.py" line="31" />
            <source>&amp;Autoconfigure on this prosthesis</source>
            <translation>&amp;Autokonfiguration an dieser Prothese</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_policy.py" line="35" />
            <source>Whether the prosthesis may link unconnected hand, wrist or elbow channels on its own; the change is previewed, confirmed and recorded in the fitting history</source>
            <translation>Ob die Prothese nicht verbundene Kanäle von Hand, Handgelenk oder Ellbogen selbst verbinden darf; die Änderung wird vorab gezeigt, bestätigt und in der Anpassungshistorie festgehalten</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_policy.py" line="78" />
            <source>Autoconfigure: …</source>
            <translation>Autokonfiguration: …</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_policy.py" line="79" />
            <source>Reading the prosthesis's policy…</source>
            <translation>Die Einstellung der Prothese wird gelesen…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_policy.py" line="84" />
            <source>Autoconfigure: on</source>
            <translation>Autokonfiguration: an</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_policy.py" line="86" />
            <source>This prosthesis links unconnected hand, wrist or elbow channels on its own when it starts or a part is swapped (Bus menu to change)</source>
            <translation>Diese Prothese verbindet nicht verbundene Kanäle von Hand, Handgelenk oder Ellbogen selbst, wenn sie startet oder ein Teil getauscht wird (im Menü Bus zu ändern)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_policy.py" line="90" />
            <source>Autoconfigure: off</source>
            <translation>Autokonfiguration: aus</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_policy.py" line="92" />
            <source>This prosthesis repairs its known links and finds replacements for swapped parts, but links nothing new on its own (Bus menu to change)</source>
            <translation>Diese Prothese stellt ihre bekannten Verbindungen wieder her und findet Ersatz für getauschte Teile, verbindet aber nichts Neues von selbst (im Menü Bus zu ändern)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_policy.py" line="106" />
            <source>Turn autoconfigure on</source>
            <translation>Autokonfiguration einschalten</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_policy.py" line="107" />
            <source>Turn autoconfigure off</source>
            <translation>Autokonfiguration ausschalten</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window/controllers/policy.py" line="133" />
            <source>Read the policy</source>
            <translation>Die Einstellung der Prothese lesen</translation>
        </message>
        <message numerus="yes">
            <location filename="../../pdcp_studio/app/window/controllers/policy.py" line="148" />
            <source>Every link stays as it is (%n link(s)); from now on unconnected hand, wrist or elbow channels stay unconnected until you link them:</source>
            <translation>
                <numerusform>Jede Verbindung bleibt, wie sie ist (%n Verbindung); ab jetzt bleiben nicht verbundene Kanäle von Hand, Handgelenk oder Ellbogen unverbunden, bis Sie sie verbinden:</numerusform>
                <numerusform>Jede Verbindung bleibt, wie sie ist (%n Verbindungen); ab jetzt bleiben nicht verbundene Kanäle von Hand, Handgelenk oder Ellbogen unverbunden, bis Sie sie verbinden:</numerusform>
            </translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window/controllers/policy.py" line="151" />
            <source>No link is removed (there are none); from now on unconnected hand, wrist or elbow channels stay unconnected until you link them.</source>
            <translation>Keine Verbindung wird entfernt (es gibt keine); ab jetzt bleiben nicht verbundene Kanäle von Hand, Handgelenk oder Ellbogen unverbunden, bis Sie sie verbinden.</translation>
        </message>
    </context>
    <context>
        <name>ProfileTreeDialog</name>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="429" />
            <source>Profile tree</source>
            <translation>Profilbaum</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="445" />
            <source>Unsaved profile tree</source>
            <translation>Ungespeicherter Profilbaum</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="446" />
            <source>Discard the unsaved changes to the profile tree?</source>
            <translation>Die ungespeicherten Änderungen am Profilbaum verwerfen?</translation>
        </message>
        <message>
            <source>Profile trees</source>
            <translation>Profilbäume</translation>
        </message>
    </context>
    <context>
        <name>ProfileTreeEditor</name>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="130" />
            <source>Name</source>
            <translation>Name</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="130" />
            <source>Component</source>
            <translation>Komponente</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="130" />
            <source>Profile</source>
            <translation>Profil</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="149" />
            <source>Add root</source>
            <translation>Wurzel hinzufügen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="151" />
            <source>Add child</source>
            <translation>Unterknoten hinzufügen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="153" />
            <source>Remove</source>
            <translation>Entfernen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="156" />
            <source>Undo</source>
            <translation>Rückgängig</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="158" />
            <source>Redo</source>
            <translation>Wiederholen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="163" />
            <source>Open…</source>
            <translation>Öffnen…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="164" />
            <source>Save</source>
            <translation>Speichern</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="165" />
            <source>Save as…</source>
            <translation>Speichern unter…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="222" />
            <source>Add: {err}</source>
            <translation>Hinzufügen: {err}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="227" />
            <source>Add: {v0} has no free component</source>
            <translation>Hinzufügen: {v0} hat keine freie Komponente</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="354" />
            <source>Rename: a profile node needs a name</source>
            <translation>Umbenennen: Ein Profilknoten braucht einen Namen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="360" />
            <source>Renumber: {text!r} is not a hex digit 1…F</source>
            <translation>Umnummerieren: {text!r} ist keine Hex-Ziffer 1…F</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="378" />
            <source>Save: no file name given</source>
            <translation>Speichern: kein Dateiname angegeben</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="384" />
            <source>Save {target}: {v1}</source>
            <translation>{target} speichern: {v1}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="406" />
            <source>Open profile tree</source>
            <translation>Profilbaum öffnen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="408" />
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="417" />
            <source>Profile trees (*.json)</source>
            <translation>Profilbäume (*.json)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/profile_tree_editor.py" line="415" />
            <source>Save profile tree</source>
            <translation>Profilbaum speichern</translation>
        </message>
        <message>
            <source>Assigned by {vendor}</source>
            <translation>Vergeben von {vendor}</translation>
        </message>
        <message>
            <source>{title} — {n_items}</source>
            <translation>{title} — {n_items}</translation>
        </message>
        <message numerus="yes">
            <source>%n node(s)</source>
            <translation>
                <numerusform>%n Knoten</numerusform>
                <numerusform>%n Knoten</numerusform>
            </translation>
        </message>
    </context>
    <context>
        <name>RecentMenu</name>
        <message>
            <location filename="../../pdcp_studio/app/recent_files.py" line="49" />
            <source>Open &amp;Recent</source>
            <translation>&amp;Zuletzt geöffnet</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/recent_files.py" line="66" />
            <source>No recent files</source>
            <translation>Keine zuletzt geöffneten Dateien</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/recent_files.py" line="69" />
            <source>&amp;Clear the list</source>
            <translation>Liste &amp;leeren</translation>
        </message>
    </context>
    <context>
        <name>RecoveryDialog</name>
        <message>
            <location filename="../../pdcp_studio/app/recovery.py" line="266" />
            <source>Recover unsaved work</source>
            <translation>Ungespeicherte Arbeit wiederherstellen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/recovery.py" line="276" />
            <source>Restore</source>
            <translation>Wiederherstellen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/recovery.py" line="278" />
            <source>Discard all</source>
            <translation>Alle verwerfen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/recovery.py" line="286" />
            <source>PDCP Studio did not close cleanly. These unsaved documents were autosaved:</source>
            <translation>PDCP Studio wurde nicht ordnungsgemäß beendet. Diese ungespeicherten Dokumente wurden automatisch gesichert:</translation>
        </message>
    </context>
    <context>
        <name>WindowRecovery</name>
        <message>
            <location filename="../../pdcp_studio/app/window_recovery.py" line="56" />
            <source>Cannot recover</source>
            <translation>Wiederherstellen nicht möglich</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/window_recovery.py" line="61" />
            <source>Recovered unsaved work: {title}</source>
            <translation>Ungespeicherte Arbeit wiederhergestellt: {title}</translation>
        </message>
    </context>
    <context>
        <name>SerialPage</name>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="283" />
            <source>/dev/ttyUSB0, COM3 or socket://host:port</source>
            <translation>/dev/ttyUSB0, COM3 oder socket://host:port</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="291" />
            <source>A hardware arbitrator's host link:</source>
            <translation>Host-Verbindung eines Hardware-Arbiters:</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="292" />
            <source>Port</source>
            <translation>Anschluss</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="293" />
            <source>Baud</source>
            <translation>Baud</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="309" />
            <source>No serial port found</source>
            <translation>Kein serieller Anschluss gefunden</translation>
        </message>
        <message numerus="yes">
            <source>%n port(s) found</source>
            <translation>
                <numerusform>%n Anschluss gefunden</numerusform>
                <numerusform>%n Anschlüsse gefunden</numerusform>
            </translation>
        </message>
    </context>
    <context>
        <name>SessionBridge</name>
        <message>
            <location filename="../../pdcp_studio/app/session_bridge.py" line="170" />
            <source>{description}: the bus connection is closed</source>
            <extracomment>Events handled per timer tick; the rest wait for the next tick so the GUI stays responsive.</extracomment>
            <translation>{description}: Die Busverbindung ist geschlossen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/session_bridge.py" line="224" />
            <source>{what}: only a simulated bus has simulator controls</source>
            <translation>{what}: Nur ein simulierter Bus hat Simulator-Steuerungen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/session_bridge.py" line="261" />
            <source>Script {name}: only a simulated bus has simulator controls</source>
            <translation>Skript {name}: Nur ein simulierter Bus hat Simulator-Steuerungen</translation>
        </message>
    </context>
    <context>
        <name>SimPage</name>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="133" />
            <source>A built-in prosthesis on an in-process virtual bus:</source>
            <translation>Eine eingebaute Prothese auf einem virtuellen Bus im Programm:</translation>
        </message>
    </context>
    <context>
        <name>SimPanel</name>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="60" />
            <source>Device</source>
            <translation>Gerät</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="60" />
            <source>VID/PID/SN</source>
            <translation>VID/PID/SN</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="60" />
            <source>Power</source>
            <translation>Strom</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="60" />
            <source>On bus</source>
            <translation>Am Bus</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="67" />
            <source>Plug in</source>
            <translation>Anstecken</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="68" />
            <source>Unplug</source>
            <translation>Abziehen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="70" />
            <source>An unplugged simulated device to put in its place</source>
            <translation>Ein abgezogenes simuliertes Gerät, das an seine Stelle tritt</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="71" />
            <source>Replace by</source>
            <translation>Ersetzen durch</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="72" />
            <source>Reset arbitrator</source>
            <translation>Arbiter zurücksetzen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="74" />
            <source>Restart the arbitrator; its stored configuration is kept, start-up recalls it</source>
            <translation>Den Arbiter neu starten; seine gespeicherte Konfiguration bleibt, der Hochlauf ruft sie ab</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="76" />
            <source>Reset, erase memory</source>
            <translation>Zurücksetzen, Speicher löschen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="79" />
            <source>A replaced arbitrator: start-up rebuilds the links from what the devices store</source>
            <translation>Ein ausgetauschter Arbiter: Der Hochlauf baut die Verbindungen aus dem auf, was die Geräte speichern</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="82" />
            <source>Store links</source>
            <translation>Verbindungen speichern</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="84" />
            <source>Store the current links as the arbitrator's configuration</source>
            <translation>Die aktuellen Verbindungen als Konfiguration des Arbiters speichern</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="87" />
            <source>Run script</source>
            <translation>Skript ausführen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="103" />
            <source>Devices</source>
            <translation>Geräte</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="110" />
            <source>Arbitrator</source>
            <translation>Arbiter</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="114" />
            <source>Scripted events</source>
            <translation>Skriptereignisse</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="126" />
            <source>Events</source>
            <translation>Ereignisse</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="143" />
            <source>Simulator</source>
            <translation>Simulator</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="212" />
            <source>on</source>
            <translation>an</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="212" />
            <source>off</source>
            <translation>aus</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="213" />
            <source>joined</source>
            <translation>beigetreten</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/sim_panel.py" line="213" />
            <source>left</source>
            <translation>verlassen</translation>
        </message>
        <message>
            <source>Problem: {message}</source>
            <translation>Problem: {message}</translation>
        </message>
        <message>
            <source>{device} joined the bus</source>
            <translation>{device} ist dem Bus beigetreten</translation>
        </message>
        <message>
            <source>{device} left the bus</source>
            <translation>{device} hat den Bus verlassen</translation>
        </message>
        <message>
            <source>Done: {what}</source>
            <translation>Erledigt: {what}</translation>
        </message>
        <message>
            <source>Script {name}: ended in the expected links</source>
            <translation>Skript {name}: endete mit den erwarteten Verbindungen</translation>
        </message>
        <message>
            <source>Script {name}: the links differ from the expected ones — {diff}</source>
            <translation>Skript {name}: die Verbindungen weichen von den erwarteten ab — {diff}</translation>
        </message>
        <message>
            <source>Plugging in {device}…</source>
            <translation>Stecke {device} ein…</translation>
        </message>
        <message>
            <source>Unplugging {device}…</source>
            <translation>Ziehe {device} ab…</translation>
        </message>
        <message>
            <source>Replacing {old} by {new}…</source>
            <translation>Ersetze {old} durch {new}…</translation>
        </message>
        <message>
            <source>Resetting the arbitrator, keeping its memory…</source>
            <translation>Setze den Arbitrator zurück, sein Speicher bleibt…</translation>
        </message>
        <message>
            <source>Resetting the arbitrator, erasing its memory…</source>
            <translation>Setze den Arbitrator zurück und lösche seinen Speicher…</translation>
        </message>
        <message>
            <source>Storing the current links…</source>
            <translation>Speichere die aktuellen Verbindungen…</translation>
        </message>
        <message>
            <source>Running script {name}…</source>
            <translation>Führe Skript {name} aus…</translation>
        </message>
    </context>
    <context>
        <name>SimScripts</name>
        <message>
            <source>Start-up</source>
            <translation>Hochlauf</translation>
        </message>
        <message>
            <source>Thesis test</source>
            <translation>Test aus der Thesis</translation>
        </message>
        <message>
            <source>Swap while running</source>
            <translation>Tausch im Betrieb</translation>
        </message>
        <message>
            <source>Unplug and plug back in</source>
            <translation>Abziehen und wieder anstecken</translation>
        </message>
        <message>
            <source>Reset, keep memory</source>
            <translation>Zurücksetzen, Speicher behalten</translation>
        </message>
        <message>
            <source>Reset, erase memory</source>
            <translation>Zurücksetzen, Speicher löschen</translation>
        </message>
        <message>
            <source>power on: the arbitrator binds, sets up and runs start-up</source>
            <translation>Einschalten: Der Arbiter bindet die Geräte, richtet sie ein und führt den Hochlauf aus</translation>
        </message>
        <message>
            <source>Test 1: D1.O1 → D2.I1 autoconfigured and stored; D2 is replaced by D3 and the prosthesis restarts: find_replacements links D1.O1 → D3.I1</source>
            <translation>Test 1: D1.O1 → D2.I1 wird automatisch verbunden und gespeichert; D2 wird durch D3 ersetzt und die Prothese neu gestartet: find_replacements verbindet D1.O1 → D3.I1</translation>
        </message>
        <message>
            <source>Test 1 without a restart: D2 is pulled and D3 plugged in while running; the duty cycle repairs the link</source>
            <translation>Test 1 ohne Neustart: D2 wird im Betrieb abgezogen und D3 angesteckt; der Arbeitszyklus repariert die Verbindung</translation>
        </message>
        <message>
            <source>Test 2: no stored configuration: autoconfigure (appendix D's links)</source>
            <translation>Test 2: keine gespeicherte Konfiguration: automatisch verbinden (die Verbindungen aus Anhang D)</translation>
        </message>
        <message>
            <source>Test 3: configure, save, reset the arbitrator keeping its memory: start-up recalls the stored configuration</source>
            <translation>Test 3: konfigurieren, speichern, den Arbiter zurücksetzen, sein Speicher bleibt: Der Hochlauf ruft die gespeicherte Konfiguration ab</translation>
        </message>
        <message>
            <source>Test 4: D1.O1 → D3.I2 autoconfigured and stored; D1 is replaced by D2 and the prosthesis restarts: find_replacements links D2.O2 → D3.I2</source>
            <translation>Test 4: D1.O1 → D3.I2 wird automatisch verbunden und gespeichert; D1 wird durch D2 ersetzt und die Prothese neu gestartet: find_replacements verbindet D2.O2 → D3.I2</translation>
        </message>
        <message>
            <source>Test 4 without a restart: D1 is pulled and D2 plugged in while running</source>
            <translation>Test 4 ohne Neustart: D1 wird im Betrieb abgezogen und D2 angesteckt</translation>
        </message>
        <message>
            <source>Test 5: configure, then reset the arbitrator with its memory erased (a replaced arbitrator): start-up rebuilds the links from the devices' source fields</source>
            <translation>Test 5: konfigurieren, dann den Arbiter mit gelöschtem Speicher zurücksetzen (ein ausgetauschter Arbiter): Der Hochlauf baut die Verbindungen aus den Quellfeldern der Geräte neu auf</translation>
        </message>
        <message>
            <source>reset the arbitrator keeping its memory</source>
            <translation>den Arbiter zurücksetzen, sein Speicher bleibt erhalten</translation>
        </message>
        <message>
            <source>reset the arbitrator with its memory erased: rebuild from devices</source>
            <translation>den Arbiter mit gelöschtem Speicher zurücksetzen: Neuaufbau aus den Geräten</translation>
        </message>
        <message>
            <source>pull {device} and plug it back in: it keeps its sources and the arbitrator links it again</source>
            <translation>{device} abziehen und wieder anstecken: Es behält seine Quellen, und der Arbiter verbindet es erneut</translation>
        </message>
    </context>
    <context>
        <name>Style</name>
        <message>
            <location filename="../../pdcp_studio/app/graph/style.py" line="28" />
            <source>Sensor</source>
            <translation>Sensor</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/style.py" line="29" />
            <source>Control</source>
            <translation>Steuerung</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/style.py" line="30" />
            <source>Terminal device</source>
            <translation>Endgerät</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/graph/style.py" line="31" />
            <source>Missing</source>
            <translation>Fehlt</translation>
        </message>
    </context>
    <context>
        <name>TransactionFlow</name>
        <message>
            <location filename="../../pdcp_studio/app/transaction_flow.py" line="125" />
            <source>Nothing to write: the project and the prosthesis agree</source>
            <extracomment>Set to cancel the running transaction (the progress dialog's Cancel does). ``confirm(title, preview) -&gt; bool`` replaces the dialog (tests).</extracomment>
            <translation>Nichts zu schreiben: Projekt und Prothese stimmen überein</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/transaction_flow.py" line="136" />
            <source>Write to prosthesis</source>
            <translation>Auf die Prothese schreiben</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/transaction_flow.py" line="156" />
            <source>Undo on the prosthesis: {0}</source>
            <translation>Auf der Prothese rückgängig machen: {0}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/transaction_flow.py" line="177" />
            <source>Redo on the prosthesis: {0}</source>
            <translation>Auf der Prothese wiederholen: {0}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/transaction_flow.py" line="185" />
            <source>not connected to a prosthesis</source>
            <translation>nicht mit einer Prothese verbunden</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/transaction_flow.py" line="188" />
            <source>A change to the prosthesis is still running</source>
            <translation>Eine Änderung an der Prothese läuft noch</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/transaction_flow.py" line="195" />
            <source>Preview the change</source>
            <translation>Vorschau der Änderung</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/transaction_flow.py" line="213" />
            <source>{0}: nothing to change on the prosthesis</source>
            <translation>{0}: An der Prothese ist nichts zu ändern</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/transaction_flow.py" line="219" />
            <source>{0}: not confirmed, nothing written</source>
            <translation>{0}: nicht bestätigt, nichts geschrieben</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/transaction_flow.py" line="258" />
            <source>Writing to the prosthesis…</source>
            <translation>Es wird auf die Prothese geschrieben…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/transaction_flow.py" line="258" />
            <source>Cancel</source>
            <translation>Abbrechen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/transaction_flow.py" line="274" />
            <source>Cancelling… (the prosthesis is put back as it was)</source>
            <translation>Wird abgebrochen… (die Prothese wird in den vorigen Zustand zurückversetzt)</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/transaction_flow.py" line="293" />
            <source>The prosthesis changed after the preview, so nothing was written. Look at the pending changes again and write them.</source>
            <translation>Die Prothese hat sich nach der Vorschau geändert, daher wurde nichts geschrieben. Die vorgemerkten Änderungen erneut ansehen und schreiben.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/transaction_flow.py" line="296" />
            <source>{0}
The prosthesis is as it was before.</source>
            <translation>{0}
Die Prothese ist wie zuvor.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/transaction_flow.py" line="312" />
            <source>{0}: cancelled</source>
            <translation>{0}: abgebrochen</translation>
        </message>
        <message numerus="yes">
            <source>Write to prosthesis (%n change(s))</source>
            <translation>
                <numerusform>Auf die Prothese schreiben (%n Änderung)</numerusform>
                <numerusform>Auf die Prothese schreiben (%n Änderungen)</numerusform>
            </translation>
        </message>
    </context>
    <context>
        <name>WriteConfigDialog</name>
        <message>
            <location filename="../../pdcp_studio/app/write_config_dialog.py" line="80" />
            <source>Write configuration to the arbitrator</source>
            <translation>Konfiguration in den Arbiter schreiben</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/write_config_dialog.py" line="96" />
            <source>Configuration</source>
            <translation>Konfiguration</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/write_config_dialog.py" line="96" />
            <source>Change</source>
            <translation>Änderung</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/write_config_dialog.py" line="96" />
            <source>Output</source>
            <translation>Ausgang</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/write_config_dialog.py" line="96" />
            <source>Input</source>
            <translation>Eingang</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/write_config_dialog.py" line="109" />
            <source>Write to arbitrator</source>
            <translation>In den Arbiter schreiben</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/write_config_dialog.py" line="137" />
            <source>Close</source>
            <translation>Schließen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/write_config_dialog.py" line="137" />
            <source>Cancel</source>
            <translation>Abbrechen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/write_config_dialog.py" line="143" />
            <source>Reading the arbitrator's stored configuration…</source>
            <translation>Die gespeicherte Konfiguration des Arbiters wird gelesen…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/write_config_dialog.py" line="173" />
            <source>{head} {change} The stored configuration decides the links the prosthesis makes at its next start-up.</source>
            <translation>{head} {change} Die gespeicherte Konfiguration bestimmt die Verbindungen, die die Prothese beim nächsten Hochlauf herstellt.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/write_config_dialog.py" line="202" />
            <source>Writing…</source>
            <translation>Wird geschrieben…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/write_config_dialog.py" line="229" />
            <source>&lt;b style='color:#b00000'&gt;Verification failed:&lt;/b&gt; {reason}. The arbitrator keeps its previous configuration.</source>
            <translation>&lt;b style='color:#b00000'&gt;Prüfung fehlgeschlagen:&lt;/b&gt; {reason}. Der Arbiter behält seine vorige Konfiguration.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/write_config_dialog.py" line="255" />
            <source>Written. Reading back to verify…</source>
            <translation>Geschrieben. Wird zur Prüfung zurückgelesen…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/write_config_dialog.py" line="278" />
            <source>&lt;b&gt;Verified:&lt;/b&gt; {message}.</source>
            <translation>&lt;b&gt;Geprüft:&lt;/b&gt; {message}.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/write_config_dialog.py" line="282" />
            <source>&lt;b style='color:#b00000'&gt;Verification failed:&lt;/b&gt; {message}. Do not rely on the stored configuration; write it again.</source>
            <translation>&lt;b style='color:#b00000'&gt;Prüfung fehlgeschlagen:&lt;/b&gt; {message}. Verlassen Sie sich nicht auf die gespeicherte Konfiguration; schreiben Sie sie erneut.</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/write_config_dialog.py" line="291" />
            <source>&lt;b style='color:#b00000'&gt;Failed:&lt;/b&gt; {message}</source>
            <translation>&lt;b style='color:#b00000'&gt;Fehlgeschlagen:&lt;/b&gt; {message}</translation>
        </message>
        <message>
            <source>The arbitrator stores no configuration yet.</source>
            <translation>Der Arbiter speichert noch keine Konfiguration.</translation>
        </message>
        <message numerus="yes">
            <source>The arbitrator stores %n configuration(s).</source>
            <translation>
                <numerusform>Der Arbiter speichert %n Konfiguration.</numerusform>
                <numerusform>Der Arbiter speichert %n Konfigurationen.</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>Writing changes nothing (%n link(s) kept).</source>
            <translation>
                <numerusform>Das Schreiben ändert nichts (%n Verbindung bleibt).</numerusform>
                <numerusform>Das Schreiben ändert nichts (%n Verbindungen bleiben).</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>Writing adds %n link(s)</source>
            <translation>
                <numerusform>Das Schreiben ergänzt %n Verbindung</numerusform>
                <numerusform>Das Schreiben ergänzt %n Verbindungen</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>, removes %n</source>
            <translation>
                <numerusform>, entfernt %n</numerusform>
                <numerusform>, entfernt %n</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>, changes the records of %n</source>
            <translation>
                <numerusform>, ändert die Einträge von %n</numerusform>
                <numerusform>, ändert die Einträge von %n</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source> and keeps %n.</source>
            <translation>
                <numerusform> und behält %n.</numerusform>
                <numerusform> und behält %n.</numerusform>
            </translation>
        </message>
        <message>
            <source>the arbitrator reports no stored configuration after the write</source>
            <translation>der Arbiter meldet nach dem Schreiben keine gespeicherte Konfiguration</translation>
        </message>
        <message>
            <source>read back {links} in {configurations}: identical</source>
            <translation>zurückgelesen: {links} in {configurations}, identisch</translation>
        </message>
        <message numerus="yes">
            <source>%n link(s)</source>
            <translation>
                <numerusform>%n Verbindung</numerusform>
                <numerusform>%n Verbindungen</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>%n configuration(s)</source>
            <translation>
                <numerusform>%n Konfiguration</numerusform>
                <numerusform>%n Konfigurationen</numerusform>
            </translation>
        </message>
    </context>
    <context>
        <name>_DetectingPage</name>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="166" />
            <source>Detect</source>
            <translation>Erkennen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="179" />
            <source>Detecting…</source>
            <translation>Wird erkannt…</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/connect_dialog.py" line="187" />
            <source>Detection failed: {message}</source>
            <translation>Erkennung fehlgeschlagen: {message}</translation>
        </message>
        <message>
            <source>Looking for adapters… this can take a few seconds</source>
            <translation>Suche nach Adaptern… das kann einige Sekunden dauern</translation>
        </message>
    </context>
    <context>
        <name>_EndEditor</name>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="164" />
            <source>Enter the numbers below</source>
            <translation>Die Nummern unten eingeben</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="167" />
            <source>Channel</source>
            <translation>Kanal</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="169" />
            <source>Vendor ID</source>
            <translation>Hersteller-ID</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="170" />
            <source>Product ID</source>
            <translation>Produkt-ID</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="171" />
            <source>Serial number</source>
            <translation>Seriennummer</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="172" />
            <source>Channel index</source>
            <translation>Kanalnummer</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="178" />
            <source>Channel type</source>
            <translation>Kanaltyp</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/config_view.py" line="179" />
            <source>Channel profile</source>
            <translation>Kanalprofil</translation>
        </message>
    </context>
    <context>
        <name>workers</name>
        <message>
            <location filename="../../pdcp_studio/app/workers.py" line="223" />
            <source>Cancelling…</source>
            <extracomment>Progress reports closer together than this are dropped (the last one always gets through), so a chatty loop cannot flood the GUI thread's event queue.</extracomment>
            <translation>Wird abgebrochen…</translation>
        </message>
    </context>
    <context>
        <name>Findings</name>
        <message>
            <source>{a} has no profile, so it can never be connected automatically. Set its profile in the inspector.</source>
            <translation>{a} hat kein Profil und kann daher nie automatisch verbunden werden. Setzen Sie sein Profil im Inspektor.</translation>
        </message>
        <message>
            <source>{a} has a profile with a gap in it, so matching ignores part of it. Check its profile in the inspector.</source>
            <translation>{a} hat ein Profil mit einer Lücke, daher wird ein Teil davon beim Abgleich übergangen. Prüfen Sie sein Profil im Inspektor.</translation>
        </message>
        <message>
            <source>{a} says it needs a channel of its device that is not an input. The device's description is wrong: ask its maker.</source>
            <translation>{a} gibt an, einen Kanal seines Geräts zu brauchen, der kein Eingang ist. Die Gerätebeschreibung ist falsch: fragen Sie den Hersteller.</translation>
        </message>
        <message>
            <source>{a} says it would like a channel of its device that is not an input. The device's description is wrong: ask its maker.</source>
            <translation>{a} gibt an, einen Kanal seines Geräts zu wünschen, der kein Eingang ist. Die Gerätebeschreibung ist falsch: fragen Sie den Hersteller.</translation>
        </message>
        <message>
            <source>{a} has no terminal profile, so it is connected before all others. Set its terminal profile if that is not intended.</source>
            <translation>{a} hat kein Endgeräteprofil und wird daher vor allen anderen verbunden. Setzen Sie sein Endgeräteprofil, wenn das nicht gewollt ist.</translation>
        </message>
        <message>
            <source>The link {a} → {b} carries no data: a device at one end is not on the bus. Plug the device in, or remove the link.</source>
            <translation>Die Verbindung {a} → {b} überträgt keine Daten: ein Gerät an einem Ende ist nicht am Bus. Stecken Sie das Gerät ein oder entfernen Sie die Verbindung.</translation>
        </message>
        <message>
            <source>The link {a} → {b} joins a device to itself. Remove it.</source>
            <translation>Die Verbindung {a} → {b} verbindet ein Gerät mit sich selbst. Entfernen Sie sie.</translation>
        </message>
        <message>
            <source>{a} feeds several inputs that each need it for themselves. Keep one of these links and remove the others.</source>
            <translation>{a} speist mehrere Eingänge, die ihn jeweils für sich allein brauchen. Behalten Sie eine dieser Verbindungen und entfernen Sie die anderen.</translation>
        </message>
        <message>
            <source>{a} is given more than one source. Keep one link into it and remove the others.</source>
            <translation>{a} hat mehr als eine Quelle. Behalten Sie eine Verbindung dorthin und entfernen Sie die anderen.</translation>
        </message>
        <message>
            <source>{a} remembers a different source than it is linked to. Writing the configuration again fixes this.</source>
            <translation>{a} hat sich eine andere Quelle gemerkt, als mit ihm verbunden ist. Ein erneutes Schreiben der Konfiguration behebt das.</translation>
        </message>
        <message>
            <source>{a} is in use but the input it needs, {b}, is not connected. Connect a source to it, or let Autoconfigure do it.</source>
            <translation>{a} wird benutzt, aber der Eingang, den er braucht, {b}, ist nicht verbunden. Verbinden Sie eine Quelle damit oder lassen Sie die Autokonfiguration das tun.</translation>
        </message>
        <message>
            <source>{a} is in use and would work better with {b} connected. Connect a source to it if one is available.</source>
            <translation>{a} wird benutzt und würde mit verbundenem {b} besser arbeiten. Verbinden Sie eine Quelle damit, wenn eine vorhanden ist.</translation>
        </message>
        <message>
            <source>{a} drives a part of the prosthesis but nothing feeds it, so that part will not move. Connect a matching output, or let Autoconfigure do it.</source>
            <translation>{a} steuert ein Teil der Prothese, bekommt aber keine Daten, daher bewegt sich dieses Teil nicht. Verbinden Sie einen passenden Ausgang oder lassen Sie die Autokonfiguration das tun.</translation>
        </message>
    </context>
    <context>
        <name>DeviceFinder</name>
        <message>
            <source>Go to device</source>
            <translation>Gehe zu Gerät</translation>
        </message>
        <message>
            <source>Device name or VID/PID/serial</source>
            <translation>Gerätename oder VID/PID/Seriennummer</translation>
        </message>
    </context>
    <context>
        <name>GraphFooter</name>
        <message>
            <source>Legend</source>
            <translation>Legende</translation>
        </message>
        <message>
            <source>Show or hide what the colours mean</source>
            <translation>Zeigen oder verbergen, was die Farben bedeuten</translation>
        </message>
        <message>
            <source>Overview</source>
            <translation>Übersicht</translation>
        </message>
        <message>
            <source>Show or hide the whole graph in small, to move around a large prosthesis</source>
            <translation>Den ganzen Graphen verkleinert zeigen oder verbergen, um sich in einer großen Prothese zu bewegen</translation>
        </message>
    </context>
    <context>
        <name>Overview</name>
        <message>
            <source>The whole graph: click or drag to show that part</source>
            <translation>Der ganze Graph: klicken oder ziehen, um diesen Teil zu zeigen</translation>
        </message>
    </context>
    <context>
        <name>Wizards</name>
        <message>
            <source>&amp;Tasks</source>
            <translation>&amp;Aufgaben</translation>
        </message>
        <message>
            <source>&amp;New fitting…</source>
            <translation>&amp;Neue Versorgung…</translation>
        </message>
        <message>
            <source>Connect, scan, check, link and store a prosthesis step by step</source>
            <translation>Eine Prothese Schritt für Schritt verbinden, durchsuchen, prüfen, verknüpfen und speichern</translation>
        </message>
        <message>
            <source>&amp;Replace a part…</source>
            <translation>Ein Teil &amp;ersetzen…</translation>
        </message>
        <message>
            <source>Swap a part and link the new one in its place step by step</source>
            <translation>Ein Teil tauschen und das neue Schritt für Schritt an seiner Stelle verbinden</translation>
        </message>
        <message>
            <source>Re&amp;store a configuration…</source>
            <translation>Eine Konfiguration &amp;wiederherstellen…</translation>
        </message>
        <message>
            <source>Put a configuration file or an earlier fitting back on the prosthesis</source>
            <translation>Eine Konfigurationsdatei oder eine frühere Versorgung wieder auf die Prothese bringen</translation>
        </message>
        <message>
            <source>The prosthesis keeps its links in its stored configuration: after a restart, or when a part is replaced, it links the parts as stored.</source>
            <translation>Die Prothese bewahrt ihre Verbindungen in der gespeicherten Konfiguration auf: Nach einem Neustart oder wenn ein Teil ersetzt wird, verbindet sie die Teile wie gespeichert.</translation>
        </message>
        <message>
            <source>Every part is already linked as autoconfigure would link it.</source>
            <translation>Jedes Teil ist bereits so verbunden, wie die Autokonfiguration es verbinden würde.</translation>
        </message>
        <message>
            <source>New fitting</source>
            <translation>Neue Versorgung</translation>
        </message>
        <message>
            <source>Autoconfigure</source>
            <translation>Autokonfiguration</translation>
        </message>
        <message>
            <source>PDCP Studio proposes the links between the parts: each one below with why it is made. Nothing is written yet.</source>
            <translation>PDCP Studio schlägt die Verbindungen zwischen den Teilen vor: jede unten mit ihrem Grund. Noch wird nichts geschrieben.</translation>
        </message>
        <message>
            <source>Write</source>
            <translation>Schreiben</translation>
        </message>
        <message>
            <source>The proposed links are written to the prosthesis.</source>
            <translation>Die vorgeschlagenen Verbindungen werden in die Prothese geschrieben.</translation>
        </message>
        <message>
            <source>Write to prosthesis</source>
            <translation>In die Prothese schreiben</translation>
        </message>
        <message>
            <source>Store the configuration</source>
            <translation>Konfiguration speichern</translation>
        </message>
        <message>
            <source>The links are stored in the prosthesis, so that it keeps them.</source>
            <translation>Die Verbindungen werden in der Prothese gespeichert, damit sie sie behält.</translation>
        </message>
        <message>
            <source>Store configuration</source>
            <translation>Konfiguration speichern</translation>
        </message>
        <message>
            <source>Connect</source>
            <translation>Verbinden</translation>
        </message>
        <message>
            <source>Choose the prosthesis to work on. Next connects to it.</source>
            <translation>Wählen Sie die Prothese, an der Sie arbeiten. „Weiter“ verbindet mit ihr.</translation>
        </message>
        <message>
            <source>A simulated prosthesis, to practise on:</source>
            <translation>Eine simulierte Prothese zum Üben:</translation>
        </message>
        <message>
            <source>Another connection (CAN adapter or arbitrator cable):</source>
            <translation>Eine andere Verbindung (CAN-Adapter oder serielles Kabel des Arbiters):</translation>
        </message>
        <message>
            <source>Choose…</source>
            <translation>Auswählen…</translation>
        </message>
        <message>
            <source>Scan</source>
            <translation>Suchen</translation>
        </message>
        <message>
            <source>PDCP Studio asks every part on the bus what it is and what it can do.</source>
            <translation>PDCP Studio fragt jedes Teil am Bus, was es ist und was es kann.</translation>
        </message>
        <message>
            <source>Scan again</source>
            <translation>Erneut suchen</translation>
        </message>
        <message>
            <source>Scanning the bus…</source>
            <translation>Bus wird durchsucht…</translation>
        </message>
        <message>
            <source>Scan finished.</source>
            <translation>Suche beendet.</translation>
        </message>
        <message>
            <source>Checks</source>
            <translation>Prüfungen</translation>
        </message>
        <message>
            <source>PDCP Studio checks that every part is described and linked as it asks to be.</source>
            <translation>PDCP Studio prüft, ob jedes Teil so beschrieben und verbunden ist, wie es das verlangt.</translation>
        </message>
        <message>
            <source>Show the technical detail</source>
            <translation>Technische Einzelheiten zeigen</translation>
        </message>
        <message>
            <source>Working out the change…</source>
            <translation>Die Änderung wird ermittelt…</translation>
        </message>
        <message>
            <source>Stop and put the prosthesis back</source>
            <translation>Anhalten und die Prothese zurücksetzen</translation>
        </message>
        <message>
            <source>Writing to the prosthesis…</source>
            <translation>Wird in die Prothese geschrieben…</translation>
        </message>
        <message>
            <source>Stopping… (the prosthesis is put back as it was)</source>
            <translation>Wird angehalten… (die Prothese wird zurückgesetzt, wie sie war)</translation>
        </message>
        <message>
            <source>The prosthesis changed after the preview, so nothing was written. Go back to look at it again.</source>
            <translation>Die Prothese hat sich nach der Vorschau geändert, daher wurde nichts geschrieben. Gehen Sie zurück und sehen Sie sie erneut an.</translation>
        </message>
        <message>
            <source>Verify</source>
            <translation>Prüfen</translation>
        </message>
        <message>
            <source>PDCP Studio reads the links and the stored configuration back from the prosthesis and compares them with what was written.</source>
            <translation>PDCP Studio liest die Verbindungen und die gespeicherte Konfiguration aus der Prothese zurück und vergleicht sie mit dem Geschriebenen.</translation>
        </message>
        <message>
            <source>Report</source>
            <translation>Bericht</translation>
        </message>
        <message>
            <source>The fitting is recorded in the fitting history. Save the fitting report to print it or keep it with the patient's file.</source>
            <translation>Die Versorgung ist im Versorgungsprotokoll festgehalten. Speichern Sie den Versorgungsbericht, um ihn zu drucken oder zur Patientenakte zu nehmen.</translation>
        </message>
        <message>
            <source>Save the fitting report (PDF)…</source>
            <translation>Versorgungsbericht speichern (PDF)…</translation>
        </message>
        <message>
            <source>Fitting report</source>
            <translation>Versorgungsbericht</translation>
        </message>
        <message>
            <source>PDF (*.pdf)</source>
            <translation>PDF (*.pdf)</translation>
        </message>
        <message>
            <source>Looking at the prosthesis…</source>
            <translation>Die Prothese wird angesehen…</translation>
        </message>
        <message>
            <source>No prosthesis is connected.</source>
            <translation>Keine Prothese ist verbunden.</translation>
        </message>
        <message>
            <source>The prosthesis connected now (none)</source>
            <translation>Die jetzt verbundene Prothese (keine)</translation>
        </message>
        <message>
            <source> (not on the bus)</source>
            <translation> (nicht am Bus)</translation>
        </message>
        <message>
            <source>Nothing was worked out to write.</source>
            <translation>Es wurde nichts zum Schreiben ermittelt.</translation>
        </message>
        <message>
            <source>Next goes on without writing anything.</source>
            <translation>„Weiter“ geht weiter, ohne etwas zu schreiben.</translation>
        </message>
        <message>
            <source>Stopped. The prosthesis is as it was before.</source>
            <translation>Angehalten. Die Prothese ist wie zuvor.</translation>
        </message>
        <message>
            <source>Everything is as written.</source>
            <translation>Alles ist wie geschrieben.</translation>
        </message>
        <message>
            <source>The prosthesis is not as written: look at the points above.</source>
            <translation>Die Prothese ist nicht wie geschrieben: Sehen Sie sich die Punkte oben an.</translation>
        </message>
        <message>
            <source>not recorded</source>
            <translation>nicht festgehalten</translation>
        </message>
        <message>
            <source>Nothing needed writing: the prosthesis already held it.</source>
            <translation>Es musste nichts geschrieben werden: Die Prothese hatte es schon.</translation>
        </message>
        <message>
            <source>Done:</source>
            <translation>Erledigt:</translation>
        </message>
        <message>
            <source>The prosthesis did not answer: {0}</source>
            <translation>Die Prothese hat nicht geantwortet: {0}</translation>
        </message>
        <message>
            <source>Connecting to {0}…</source>
            <translation>Verbinde mit {0}…</translation>
        </message>
        <message>
            <source>Connected to {0}.</source>
            <translation>Verbunden mit {0}.</translation>
        </message>
        <message>
            <source>Cannot connect to {0}: {1}</source>
            <translation>Keine Verbindung mit {0} möglich: {1}</translation>
        </message>
        <message>
            <source>Written, read back and verified.</source>
            <translation>Geschrieben, zurückgelesen und geprüft.</translation>
        </message>
        <message>
            <source>Every linked part is on the bus.</source>
            <translation>Jedes verbundene Teil ist am Bus.</translation>
        </message>
        <message>
            <source>The prosthesis connected now: {0}</source>
            <translation>Die jetzt verbundene Prothese: {0}</translation>
        </message>
        <message>
            <source>Another connection: {0}</source>
            <translation>Eine andere Verbindung: {0}</translation>
        </message>
        <message>
            <source>No problems found: every part is described and linked as it asks.</source>
            <translation>Keine Probleme gefunden: Jedes Teil ist beschrieben und verbunden, wie es das verlangt.</translation>
        </message>
        <message>
            <source>Nothing needs writing: the prosthesis already holds this.</source>
            <translation>Nichts muss geschrieben werden: Die Prothese hat das schon.</translation>
        </message>
        <message>
            <source>Press the button below to write this to the prosthesis. The parts that move are held still while it is written, then everything is read back and checked; on any difference the prosthesis is put back as it was.</source>
            <translation>Drücken Sie die Schaltfläche unten, um dies in die Prothese zu schreiben. Die beweglichen Teile werden dabei stillgehalten, danach wird alles zurückgelesen und geprüft; bei jeder Abweichung wird die Prothese zurückgesetzt, wie sie war.</translation>
        </message>
        <message>
            <source> Recorded in the fitting history as entry {0}.</source>
            <translation> Im Versorgungsprotokoll als Eintrag {0} festgehalten.</translation>
        </message>
        <message>
            <source>Not written: {0}. The prosthesis is as it was before.</source>
            <translation>Nicht geschrieben: {0}. Die Prothese ist wie zuvor.</translation>
        </message>
        <message>
            <source>The stored configuration reads back as written.</source>
            <translation>Die gespeicherte Konfiguration liest sich zurück wie geschrieben.</translation>
        </message>
        <message>
            <source>entry {0}</source>
            <translation>Eintrag {0}</translation>
        </message>
        <message>
            <source>Saved the fitting report: {0}</source>
            <translation>Versorgungsbericht gespeichert: {0}</translation>
        </message>
        <message>
            <source>Fitting history entry {0}: written and verified by the prosthesis.</source>
            <translation>Eintrag {0} im Versorgungsprotokoll: von der Prothese geschrieben und geprüft.</translation>
        </message>
        <message>
            <source>Scanning the bus… {0} of {1}</source>
            <translation>Bus wird durchsucht… {0} von {1}</translation>
        </message>
        <message>
            <source>Not on the prosthesis: {0}</source>
            <translation>Nicht an der Prothese: {0}</translation>
        </message>
        <message>
            <source>The stored configuration is not the one written.</source>
            <translation>Die gespeicherte Konfiguration ist nicht die geschriebene.</translation>
        </message>
        <message>
            <source>Also on the prosthesis: {0}</source>
            <translation>Zusätzlich an der Prothese: {0}</translation>
        </message>
        <message>
            <source>{0} is not on the bus.</source>
            <translation>{0} ist nicht am Bus.</translation>
        </message>
        <message>
            <source>The stored configuration will name the new part, so the next start-up links it directly.</source>
            <translation>Die gespeicherte Konfiguration nennt dann das neue Teil, sodass der nächste Start es direkt verbindet.</translation>
        </message>
        <message>
            <source>Show the Simulator panel</source>
            <translation>Simulator-Bereich zeigen</translation>
        </message>
        <message>
            <source>What is missing</source>
            <translation>Was fehlt</translation>
        </message>
        <message>
            <source>PDCP Studio compares the parts on the bus with the parts the prosthesis is linked and configured for.</source>
            <translation>PDCP Studio vergleicht die Teile am Bus mit den Teilen, für die die Prothese verbunden und konfiguriert ist.</translation>
        </message>
        <message>
            <source>Plug the new part in</source>
            <translation>Das neue Teil anschließen</translation>
        </message>
        <message>
            <source>Plug the new part in now. This page waits for it to appear on the bus.</source>
            <translation>Schließen Sie das neue Teil jetzt an. Diese Seite wartet, bis es am Bus erscheint.</translation>
        </message>
        <message>
            <source>Waiting for the new part…</source>
            <translation>Warte auf das neue Teil…</translation>
        </message>
        <message>
            <source>Replace a part</source>
            <translation>Ein Teil ersetzen</translation>
        </message>
        <message>
            <source>Replacement plan</source>
            <translation>Ersatzplan</translation>
        </message>
        <message>
            <source>How the new part takes the missing part's place: each link with why it is made and how alike the new channel is. Nothing is written yet.</source>
            <translation>Wie das neue Teil den Platz des fehlenden einnimmt: jede Verbindung mit ihrem Grund und wie ähnlich der neue Kanal ist. Noch wird nichts geschrieben.</translation>
        </message>
        <message>
            <source>The replacement is written to the prosthesis.</source>
            <translation>Der Ersatz wird in die Prothese geschrieben.</translation>
        </message>
        <message>
            <source>Next: plug the new part in.</source>
            <translation>Als Nächstes: das neue Teil anschließen.</translation>
        </message>
        <message>
            <source>Every part the prosthesis expects is on the bus.</source>
            <translation>Jedes Teil, das die Prothese erwartet, ist am Bus.</translation>
        </message>
        <message>
            <source>On this simulated prosthesis: in the Simulator panel choose {0} and press Plug in.</source>
            <translation>An dieser simulierten Prothese: Wählen Sie im Simulator-Bereich {0} und drücken Sie „Anstecken“.</translation>
        </message>
        <message>
            <source>the new part</source>
            <translation>das neue Teil</translation>
        </message>
        <message>
            <source>{0} or {1}</source>
            <translation>{0} oder {1}</translation>
        </message>
        <message>
            <source>The new part is on the bus. Next shows how it will be linked.</source>
            <translation>Das neue Teil ist am Bus. „Weiter“ zeigt, wie es verbunden wird.</translation>
        </message>
        <message>
            <source>The new part: {0}.</source>
            <translation>Das neue Teil: {0}.</translation>
        </message>
        <message>
            <source>Missing:</source>
            <translation>Es fehlt:</translation>
        </message>
        <message>
            <source>To try a swap on this simulated prosthesis: in the Simulator panel choose {0} and press Unplug. This page follows the bus and shows the missing part.</source>
            <translation>Um an dieser simulierten Prothese einen Tausch zu üben: Wählen Sie im Simulator-Bereich {0} und drücken Sie „Abziehen“. Diese Seite folgt dem Bus und zeigt das fehlende Teil.</translation>
        </message>
        <message>
            <source>a part</source>
            <translation>ein Teil</translation>
        </message>
        <message>
            <source>Nothing is missing.</source>
            <translation>Nichts fehlt.</translation>
        </message>
        <message>
            <source>New on the bus: {0}.</source>
            <translation>Neu am Bus: {0}.</translation>
        </message>
        <message>
            <source>{0} is back on the bus: it needs no replacement.</source>
            <translation>{0} ist wieder am Bus: Es braucht keinen Ersatz.</translation>
        </message>
        <message>
            <source>Choose the configuration</source>
            <translation>Konfiguration wählen</translation>
        </message>
        <message>
            <source>Choose a configuration file, or a fitting of this prosthesis from the fitting history, to put back on the prosthesis.</source>
            <translation>Wählen Sie eine Konfigurationsdatei oder eine Versorgung dieser Prothese aus dem Versorgungsprotokoll, um sie wieder auf die Prothese zu bringen.</translation>
        </message>
        <message>
            <source>From a configuration file (.pdcfg):</source>
            <translation>Aus einer Konfigurationsdatei (.pdcfg):</translation>
        </message>
        <message>
            <source>No file chosen</source>
            <translation>Keine Datei gewählt</translation>
        </message>
        <message>
            <source>Browse…</source>
            <translation>Durchsuchen…</translation>
        </message>
        <message>
            <source>From the fitting history of this prosthesis:</source>
            <translation>Aus dem Versorgungsprotokoll dieser Prothese:</translation>
        </message>
        <message>
            <source>Configuration file</source>
            <translation>Konfigurationsdatei</translation>
        </message>
        <message>
            <source>Configurations (*.pdcfg)</source>
            <translation>Konfigurationen (*.pdcfg)</translation>
        </message>
        <message>
            <source>The links on the prosthesis are already as in this configuration.</source>
            <translation>Die Verbindungen an der Prothese sind schon wie in dieser Konfiguration.</translation>
        </message>
        <message>
            <source>Restore a configuration</source>
            <translation>Eine Konfiguration wiederherstellen</translation>
        </message>
        <message>
            <source>Difference</source>
            <translation>Unterschied</translation>
        </message>
        <message>
            <source>What changes on the prosthesis when this configuration is put back. Nothing is written yet.</source>
            <translation>Was sich an der Prothese ändert, wenn diese Konfiguration wiederhergestellt wird. Noch wird nichts geschrieben.</translation>
        </message>
        <message>
            <source>The configuration is written to the prosthesis.</source>
            <translation>Die Konfiguration wird in die Prothese geschrieben.</translation>
        </message>
        <message>
            <source>No fitting of this prosthesis is recorded yet.</source>
            <translation>Für diese Prothese ist noch keine Versorgung festgehalten.</translation>
        </message>
        <message>
            <source>Connect {0}</source>
            <translation>Verbinden: {0}</translation>
        </message>
        <message>
            <source>Disconnect {0}</source>
            <translation>Trennen: {0}</translation>
        </message>
        <message>
            <source>From the file {0}.</source>
            <translation>Aus der Datei {0}.</translation>
        </message>
        <message>
            <source>As the fitting of {0} left the prosthesis (fitting history entry {1}).</source>
            <translation>So, wie die Versorgung vom {0} die Prothese hinterließ (Eintrag {1} im Versorgungsprotokoll).</translation>
        </message>
        <message>
            <source>Cannot read {0}: {1}</source>
            <translation>{0} kann nicht gelesen werden: {1}</translation>
        </message>
        <message>
            <source>nothing in common in what it does</source>
            <translation>nichts gemeinsam in dem, was er tut,</translation>
        </message>
        <message>
            <source>and sends its data the same way</source>
            <translation>und sendet seine Daten auf dieselbe Weise</translation>
        </message>
        <message>
            <source>Exact match</source>
            <translation>Genaue Übereinstimmung</translation>
        </message>
        <message>
            <source>It drives a part of the prosthesis that nothing fed.</source>
            <translation>Er steuert ein Teil der Prothese, das keine Daten bekam.</translation>
        </message>
        <message>
            <source>One end is gone; the new part takes this link over.</source>
            <translation>Ein Ende fehlt; das neue Teil übernimmt diese Verbindung.</translation>
        </message>
        <message>
            <source>The output that fed it is gone.</source>
            <translation>Der Ausgang, der ihn speiste, fehlt.</translation>
        </message>
        <message>
            <source>It is in the configuration.</source>
            <translation>Sie steht in der Konfiguration.</translation>
        </message>
        <message>
            <source>The parts remember this link.</source>
            <translation>Die Teile erinnern sich an diese Verbindung.</translation>
        </message>
        <message>
            <source>An input needs this output for itself alone.</source>
            <translation>Ein Eingang braucht diesen Ausgang für sich allein.</translation>
        </message>
        <message>
            <source>It is not in the configuration.</source>
            <translation>Sie steht nicht in der Konfiguration.</translation>
        </message>
        <message>
            <source>Every link is cleared.</source>
            <translation>Alle Verbindungen werden gelöscht.</translation>
        </message>
        <message>
            <source>it does the same job</source>
            <translation>er erfüllt dieselbe Aufgabe</translation>
        </message>
        <message>
            <source>but sends its data differently</source>
            <translation>sendet seine Daten aber anders</translation>
        </message>
        <message>
            <source>and sends its data partly the same way</source>
            <translation>und sendet seine Daten teilweise auf dieselbe Weise</translation>
        </message>
        <message>
            <source>Close match</source>
            <translation>Gute Übereinstimmung</translation>
        </message>
        <message>
            <source>Distant match</source>
            <translation>Entfernte Übereinstimmung</translation>
        </message>
        <message>
            <source>{grade}: {kind} {how} ({total} of {top} points).</source>
            <translation>{grade}: {kind} {how} ({total} von {top} Punkten).</translation>
        </message>
        <message>
            <source>A channel in use needs it to work.</source>
            <translation>Ein genutzter Kanal braucht sie, um zu arbeiten.</translation>
        </message>
        <message>
            <source>A channel in use works better with it.</source>
            <translation>Ein genutzter Kanal arbeitet mit ihr besser.</translation>
        </message>
        <message>
            <source>Disconnect</source>
            <translation>Trennen</translation>
        </message>
        <message>
            <source>The stored configuration's extra records change.</source>
            <translation>Die zusätzlichen Einträge der gespeicherten Konfiguration ändern sich.</translation>
        </message>
        <message>
            <source>Nothing changes: the prosthesis already holds this.</source>
            <translation>Nichts ändert sich: Die Prothese hat das schon.</translation>
        </message>
        <message>
            <source>It takes the place of {0}, which is gone.</source>
            <translation>Er nimmt den Platz von {0} ein, das fehlt.</translation>
        </message>
        <message>
            <source>Automatic linking of new parts: on</source>
            <translation>Automatisches Verbinden neuer Teile: ein</translation>
        </message>
        <message>
            <source>Automatic linking of new parts: off</source>
            <translation>Automatisches Verbinden neuer Teile: aus</translation>
        </message>
        <message>
            <source>it does a related job ({0} of {1} levels of its kind alike)</source>
            <translation>er erfüllt eine verwandte Aufgabe ({0} von {1} Stufen seiner Art gleich)</translation>
        </message>
        <message>
            <source>{0} needs it to work.</source>
            <translation>{0} braucht sie, um zu arbeiten.</translation>
        </message>
        <message>
            <source>{0} works better with it.</source>
            <translation>{0} arbeitet mit ihr besser.</translation>
        </message>
        <message>
            <source>Will be stored: {0}</source>
            <translation>Wird gespeichert: {0}</translation>
        </message>
        <message>
            <source>No longer stored: {0}</source>
            <translation>Nicht mehr gespeichert: {0}</translation>
        </message>
        <message>
            <source>Stored again with updated details: {0}</source>
            <translation>Mit aktualisierten Angaben erneut gespeichert: {0}</translation>
        </message>
        <message>
            <source>Held still meanwhile, so the prosthesis cannot move: {0}.</source>
            <translation>Währenddessen stillgehalten, damit sich die Prothese nicht bewegen kann: {0}.</translation>
        </message>
        <message>
            <source>New fitting: links written</source>
            <translation>Neue Versorgung: Verbindungen geschrieben</translation>
        </message>
        <message>
            <source>New fitting: configuration stored</source>
            <translation>Neue Versorgung: Konfiguration gespeichert</translation>
        </message>
        <message>
            <source>Part replaced</source>
            <translation>Teil ersetzt</translation>
        </message>
        <message>
            <source>Configuration restored from {0}</source>
            <translation>Konfiguration aus {0} wiederhergestellt</translation>
        </message>
        <message>
            <source>Fitting history entry {0} restored</source>
            <translation>Eintrag {0} des Versorgungsprotokolls wiederhergestellt</translation>
        </message>
        <message>
            <source>The links to make, each with why:</source>
            <translation>Die herzustellenden Verbindungen, jede mit ihrem Grund:</translation>
        </message>
        <message>
            <source>The links were written and verified (fitting history entry {0}).</source>
            <translation>Die Verbindungen wurden geschrieben und geprüft (Eintrag {0} im Versorgungsprotokoll).</translation>
        </message>
        <message>
            <source>Press the button below to write this to the prosthesis. It is read back and checked; on any difference the prosthesis is put back as it was.</source>
            <translation>Drücken Sie die Schaltfläche unten, um dies in die Prothese zu schreiben. Es wird zurückgelesen und geprüft; bei jeder Abweichung wird die Prothese zurückgesetzt, wie sie war.</translation>
        </message>
        <message>
            <source>When it is written:</source>
            <translation>Beim Schreiben:</translation>
        </message>
        <message>
            <source>{name} (serial {serial})</source>
            <translation>{name} (Seriennummer {serial})</translation>
        </message>
        <message>
            <source>{0} (simulated)</source>
            <translation>{0} (simuliert)</translation>
        </message>
        <message>
            <source>Warning: this fitting was made before any configuration was stored on the prosthesis. Putting it back clears the stored configuration: after a restart, or when a part is replaced, the prosthesis will no longer link its parts as they are stored now.</source>
            <translation>Achtung: Diese Versorgung wurde gemacht, bevor eine Konfiguration in der Prothese gespeichert war. Sie wiederherzustellen löscht die gespeicherte Konfiguration: Nach einem Neustart oder wenn ein Teil ersetzt wird, verbindet die Prothese ihre Teile nicht mehr so, wie sie jetzt gespeichert sind.</translation>
        </message>
        <message>
            <source>Yes, clear the stored configuration</source>
            <translation>Ja, die gespeicherte Konfiguration löschen</translation>
        </message>
        <message>
            <source>optional, e.g. the clinic&apos;s case number</source>
            <translation>freiwillig, z. B. die Fallnummer der Klinik</translation>
        </message>
        <message>
            <source>Patient reference:</source>
            <translation>Patientenreferenz:</translation>
        </message>
        <message>
            <source>Continue</source>
            <translation>Fortfahren</translation>
        </message>
        <message>
            <source>Press {0} to carry on; nothing is written.</source>
            <translation>„{0}“ drücken, um fortzufahren; es wird nichts geschrieben.</translation>
        </message>
    </context>
    <context>
        <name>ArbitratorFoundDialog</name>
        <message>
            <source>Another bus arbitrator is running</source>
            <translation>Ein anderer Bus-Arbitrator läuft</translation>
        </message>
        <message>
            <source>&lt;p&gt;&lt;b&gt;This bus already has an arbitrator&lt;/b&gt; — most likely the prosthesis's own control unit.&lt;/p&gt;&lt;p&gt;PDCP Studio did not take part in it: nothing was sent to the prosthesis. Only one arbitrator may run a bus.&lt;/p&gt;</source>
            <translation>&lt;p&gt;&lt;b&gt;Dieser Bus hat bereits einen Arbitrator&lt;/b&gt; — wahrscheinlich die eigene Steuereinheit der Prothese.&lt;/p&gt;&lt;p&gt;PDCP Studio hat sich nicht beteiligt: An die Prothese wurde nichts gesendet. Nur ein Arbitrator darf einen Bus führen.&lt;/p&gt;</translation>
        </message>
        <message>
            <source>&lt;p&gt;&lt;b&gt;Another arbitrator started on this bus&lt;/b&gt; — most likely the prosthesis's own control unit.&lt;/p&gt;&lt;p&gt;PDCP Studio stopped sending at once and disconnected: only one arbitrator may run a bus.&lt;/p&gt;</source>
            <translation>&lt;p&gt;&lt;b&gt;Auf diesem Bus hat ein anderer Arbitrator begonnen&lt;/b&gt; — wahrscheinlich die eigene Steuereinheit der Prothese.&lt;/p&gt;&lt;p&gt;PDCP Studio hat sofort aufgehört zu senden und die Verbindung getrennt: Nur ein Arbitrator darf einen Bus führen.&lt;/p&gt;</translation>
        </message>
        <message>
            <source>&lt;p&gt;You can &lt;b&gt;watch the bus&lt;/b&gt;: see its traffic in the monitor without sending anything. Or &lt;b&gt;connect through the host link&lt;/b&gt;: the prosthesis's own arbitrator answers over its serial cable, and you can read and configure it there.&lt;/p&gt;</source>
            <translation>&lt;p&gt;Sie können &lt;b&gt;den Bus beobachten&lt;/b&gt;: seinen Verkehr im Monitor sehen, ohne etwas zu senden. Oder &lt;b&gt;über die Host-Verbindung verbinden&lt;/b&gt;: Der eigene Arbitrator der Prothese antwortet über sein serielles Kabel, und Sie können ihn dort auslesen und konfigurieren.&lt;/p&gt;</translation>
        </message>
        <message>
            <source>Bus: {url}
{detail}</source>
            <translation>Bus: {url}
{detail}</translation>
        </message>
        <message>
            <source>Details</source>
            <translation>Details</translation>
        </message>
        <message>
            <source>Watch the bus (listen only)</source>
            <translation>Bus beobachten (nur mithören)</translation>
        </message>
        <message>
            <source>Connect through the host link…</source>
            <translation>Über die Host-Verbindung verbinden…</translation>
        </message>
        <message>
            <source>Show the bus's frames in the monitor; PDCP Studio sends nothing (listen-only)</source>
            <translation>Die Frames des Busses im Monitor zeigen; PDCP Studio sendet nichts (nur mithören)</translation>
        </message>
        <message>
            <source>Open the connection dialog on the serial host link</source>
            <translation>Den Verbindungsdialog bei der seriellen Host-Verbindung öffnen</translation>
        </message>
    </context>
    <context>
        <name>ListeningIndicator</name>
        <message>
            <source>Listening to {url} — sends nothing</source>
            <translation>Höre {url} mit — sendet nichts</translation>
        </message>
        <message>
            <source>Stop listening</source>
            <translation>Mithören beenden</translation>
        </message>
    </context>
    <context>
        <name>HeardBus</name>
        <message>
            <source>Device at node {node}</source>
            <translation>Gerät an Knoten {node}</translation>
        </message>
        <message>
            <source>Channel node {node}</source>
            <translation>Kanalknoten {node}</translation>
        </message>
    </context>
    <context>
        <name>ArbitratorFound</name>
        <message>
            <source>{url}: another bus arbitrator is running this bus — PDCP Studio sent nothing</source>
            <translation>{url}: Ein anderer Bus-Arbitrator führt diesen Bus — PDCP Studio hat nichts gesendet</translation>
        </message>
        <message>
            <source>Watching {url} without sending: its frames appear in the monitor</source>
            <translation>Beobachte {url} ohne zu senden: seine Frames erscheinen im Monitor</translation>
        </message>
        <message>
            <source>Stopped listening to {url}: {reason}</source>
            <translation>Mithören von {url} beendet: {reason}</translation>
        </message>
    </context>
    <context>
        <name>PlanWords</name>
        <message>
            <source>a part was replaced while the prosthesis was running</source>
            <translation>ein Teil wurde im laufenden Betrieb ersetzt</translation>
        </message>
        <message>
            <source>the prosthesis started up</source>
            <translation>die Prothese ist gestartet</translation>
        </message>
        <message>
            <source>automatic set-up</source>
            <translation>automatische Einrichtung</translation>
        </message>
        <message>
            <source>looking for replacements for missing parts</source>
            <translation>Suche nach Ersatz für fehlende Teile</translation>
        </message>
        <message>
            <source>putting the stored set-up in place</source>
            <translation>die gespeicherte Einrichtung wird umgesetzt</translation>
        </message>
        <message>
            <source>making sure inputs that need a source for themselves have it alone</source>
            <translation>Eingänge, die eine Quelle für sich allein brauchen, bekommen sie allein</translation>
        </message>
        <message>
            <source>removing every link</source>
            <translation>alle Verbindungen werden entfernt</translation>
        </message>
        <message>
            <source>a change made by hand</source>
            <translation>eine Änderung von Hand</translation>
        </message>
        <message>
            <source>it is in the stored set-up</source>
            <translation>sie ist in der gespeicherten Einrichtung</translation>
        </message>
        <message>
            <source>the devices remembered it</source>
            <translation>die Geräte haben sie sich gemerkt</translation>
        </message>
        <message>
            <source>it replaces a part that is missing</source>
            <translation>sie ersetzt ein fehlendes Teil</translation>
        </message>
        <message>
            <source>it drives a part of the prosthesis</source>
            <translation>sie steuert ein Teil der Prothese</translation>
        </message>
        <message>
            <source>another channel needs it</source>
            <translation>ein anderer Kanal braucht sie</translation>
        </message>
        <message>
            <source>another channel works better with it</source>
            <translation>ein anderer Kanal arbeitet damit besser</translation>
        </message>
        <message>
            <source>an input needs its source for itself</source>
            <translation>ein Eingang braucht seine Quelle für sich allein</translation>
        </message>
        <message>
            <source>all links are removed</source>
            <translation>alle Verbindungen werden entfernt</translation>
        </message>
        <message>
            <source>it is not in the stored set-up</source>
            <translation>sie ist nicht in der gespeicherten Einrichtung</translation>
        </message>
        <message>
            <source>one of its parts is missing; a replacement takes its place</source>
            <translation>eines ihrer Teile fehlt; ein Ersatz tritt an seine Stelle</translation>
        </message>
        <message>
            <source>the part sending to it is missing; a replacement takes its place</source>
            <translation>das sendende Teil fehlt; ein Ersatz tritt an seine Stelle</translation>
        </message>
        <message>
            <source>that output already feeds an input that needs it for itself</source>
            <translation>dieser Ausgang speist schon einen Eingang, der ihn für sich allein braucht</translation>
        </message>
        <message>
            <source>that input already has a source</source>
            <translation>dieser Eingang hat schon eine Quelle</translation>
        </message>
        <message>
            <source>no similar free channel was found</source>
            <translation>kein ähnlicher freier Kanal gefunden</translation>
        </message>
        <message>
            <source>undone: a channel it needs could not be connected</source>
            <translation>rückgängig gemacht: ein benötigter Kanal ließ sich nicht verbinden</translation>
        </message>
        <message>
            <source>already tried and refused</source>
            <translation>schon versucht und abgelehnt</translation>
        </message>
        <message>
            <source>both of its parts are missing</source>
            <translation>beide Teile fehlen</translation>
        </message>
        <message>
            <source>the device's description names a channel that is not an input</source>
            <translation>die Gerätebeschreibung nennt einen Kanal, der kein Eingang ist</translation>
        </message>
        <message>
            <source>the same part</source>
            <translation>dasselbe Teil</translation>
        </message>
        <message>
            <source>same product, other serial number</source>
            <translation>gleiches Produkt, andere Seriennummer</translation>
        </message>
        <message>
            <source>same maker, another product</source>
            <translation>gleicher Hersteller, anderes Produkt</translation>
        </message>
        <message>
            <source>another maker's product</source>
            <translation>Produkt eines anderen Herstellers</translation>
        </message>
        <message>
            <source>same kind of signal</source>
            <translation>gleiche Art Signal</translation>
        </message>
        <message>
            <source>similar signal ({depth} of {levels} levels alike)</source>
            <translation>ähnliches Signal ({depth} von {levels} Ebenen gleich)</translation>
        </message>
        <message>
            <source>another kind of signal</source>
            <translation>andere Art Signal</translation>
        </message>
        <message>
            <source>{kind}, same form</source>
            <translation>{kind}, gleiche Form</translation>
        </message>
        <message>
            <source>control mode</source>
            <translation>Steuerungsart</translation>
        </message>
        <message>
            <source>value type</source>
            <translation>Werttyp</translation>
        </message>
        <message>
            <source>value size</source>
            <translation>Wertgröße</translation>
        </message>
        <message>
            <source>{kind}; other {what}</source>
            <translation>{kind}; andere(r) {what}</translation>
        </message>
    </context>
    <context>
        <name>EventsPanel</name>
        <message>
            <source>The arbitrator changed links on its own: {why}</source>
            <translation>Der Arbiter hat selbst Verbindungen geändert: {why}</translation>
        </message>
        <message>
            <source>they read back as written</source>
            <translation>sie lesen sich zurück wie geschrieben</translation>
        </message>
        <message>
            <source>they did not all read back as written</source>
            <translation>nicht alle lesen sich zurück wie geschrieben</translation>
        </message>
        <message>
            <source>It held {parts} still while it wrote, read the links back and let go: {outcome}</source>
            <translation>Er hielt {parts} still, während er schrieb, las die Verbindungen zurück und gab sie frei: {outcome}</translation>
        </message>
        <message>
            <source>No part that moves the prosthesis needed holding; read back: {outcome}</source>
            <translation>Kein Teil, das die Prothese bewegt, musste angehalten werden; zurückgelesen: {outcome}</translation>
        </message>
        <message>
            <source>No beacon for {seconds} s: {intervals} beacon intervals of {ms} ms</source>
            <translation>Kein Beacon seit {seconds} s: {intervals} Beacon-Intervalle zu {ms} ms</translation>
        </message>
        <message>
            <source>It is no longer heard on the bus; the arbitrator gave no details</source>
            <translation>Es ist am Bus nicht mehr zu hören; der Arbitrator nannte keine Einzelheiten</translation>
        </message>
        <message>
            <source>{device} joined the bus</source>
            <translation>{device} ist dem Bus beigetreten</translation>
        </message>
        <message>
            <source>{device} left the bus</source>
            <translation>{device} hat den Bus verlassen</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/docks/events_panel.py" line="76" />
            <source>{device} is replaced by {new}</source>
            <translation>{device} ist ersetzt durch {new}</translation>
        </message>
        <message>
            <location filename="../../pdcp_studio/app/docks/events_panel.py" line="78" />
            <source>Its replacement's links are written and verified: it is no longer missing</source>
            <translation>Die Verbindungen des Ersatzteils sind geschrieben und geprüft: es fehlt nicht mehr</translation>
        </message>
        <message>
            <source>Left unconnected: {names}</source>
            <translation>Nicht verbunden gelassen: {names}</translation>
        </message>
        <message>
            <source>Bus problem</source>
            <translation>Busproblem</translation>
        </message>
        <message>
            <source>Listening for another arbitrator before taking part</source>
            <translation>Hört vor der Teilnahme auf einen anderen Arbitrator</translation>
        </message>
        <message>
            <source>PDCP Studio runs this bus</source>
            <translation>PDCP Studio führt diesen Bus</translation>
        </message>
        <message>
            <source>Another arbitrator runs this bus: PDCP Studio sends nothing</source>
            <translation>Ein anderer Arbitrator führt diesen Bus: PDCP Studio sendet nichts</translation>
        </message>
        <message>
            <source>The adapter is gone: reconnecting</source>
            <translation>Der Adapter ist weg: verbinde neu</translation>
        </message>
        <message>
            <source>The adapter is back: reading the bus again</source>
            <translation>Der Adapter ist zurück: lese den Bus neu</translation>
        </message>
        <message>
            <source>Linked {link}</source>
            <translation>Verbunden: {link}</translation>
        </message>
        <message>
            <source>Removed the link {link}</source>
            <translation>Verbindung entfernt: {link}</translation>
        </message>
        <message>
            <source> ({channel} is missing)</source>
            <translation> ({channel} fehlt)</translation>
        </message>
        <message>
            <source>Time</source>
            <translation>Zeit</translation>
        </message>
        <message>
            <source>What happened</source>
            <translation>Was geschah</translation>
        </message>
        <message>
            <source>Why</source>
            <translation>Warum</translation>
        </message>
        <message>
            <source>How similar</source>
            <translation>Wie ähnlich</translation>
        </message>
        <message>
            <source>Clear</source>
            <translation>Leeren</translation>
        </message>
        <message>
            <source>No bus events yet: parts that come and go and the links the bus makes appear here</source>
            <translation>Noch keine Busereignisse: Teile, die kommen und gehen, und die Verbindungen des Busses erscheinen hier</translation>
        </message>
        <message numerus="yes">
            <source>%n event(s)</source>
            <translation>
                <numerusform>%n Ereignis</numerusform>
                <numerusform>%n Ereignisse</numerusform>
            </translation>
        </message>
    </context>
    <context>
        <name>TraceModel</name>
        <message>
            <source>Time since start</source>
            <translation>Zeit seit Beginn</translation>
        </message>
        <message>
            <source>Clock time</source>
            <translation>Uhrzeit</translation>
        </message>
        <message>
            <source>Time since previous row</source>
            <translation>Zeit seit voriger Zeile</translation>
        </message>
        <message>
            <source>Time since marker</source>
            <translation>Zeit seit Markierung</translation>
        </message>
        <message>
            <source>Δ previous</source>
            <translation>Δ vorige</translation>
        </message>
        <message>
            <source>Δ marker</source>
            <translation>Δ Markierung</translation>
        </message>
        <message>
            <source>data frame</source>
            <translation>Datennachricht</translation>
        </message>
        <message>
            <source>remote frame</source>
            <translation>Remote-Nachricht</translation>
        </message>
        <message>
            <source>error frame</source>
            <translation>Fehlernachricht</translation>
        </message>
        <message>
            <source>FD frame</source>
            <translation>FD-Nachricht</translation>
        </message>
        <message>
            <source>extended frame</source>
            <translation>Nachricht mit erweiterter ID</translation>
        </message>
    </context>
    <context>
        <name>StatsModel</name>
        <message>
            <source>ID</source>
            <translation>ID</translation>
        </message>
        <message>
            <source>Node</source>
            <translation>Knoten</translation>
        </message>
        <message>
            <source>Count</source>
            <translation>Anzahl</translation>
        </message>
        <message>
            <source>Period (ms)</source>
            <translation>Periode (ms)</translation>
        </message>
        <message>
            <source>Last period (ms)</source>
            <translation>Letzte Periode (ms)</translation>
        </message>
        <message>
            <source>Last data</source>
            <translation>Letzte Daten</translation>
        </message>
        <message>
            <source>Meaning</source>
            <translation>Bedeutung</translation>
        </message>
    </context>
    <context>
        <name>LivePlot</name>
        <message>
            <source>value</source>
            <translation>Wert</translation>
        </message>
        <message>
            <source>position</source>
            <translation>Position</translation>
        </message>
        <message>
            <source>velocity</source>
            <translation>Geschwindigkeit</translation>
        </message>
        <message>
            <source>acceleration</source>
            <translation>Beschleunigung</translation>
        </message>
        <message>
            <source>on/off</source>
            <translation>ein/aus</translation>
        </message>
        <message>
            <source>on</source>
            <translation>ein</translation>
        </message>
        <message>
            <source>off</source>
            <translation>aus</translation>
        </message>
        <message>
            <source>Choose signals to plot: select a link or channel on the bus, or use Signals.</source>
            <translation>Signale zum Anzeigen wählen: eine Verbindung oder einen Kanal am Bus auswählen oder „Signale“ benutzen.</translation>
        </message>
        <message>
            <source>time before now (s)</source>
            <translation>Zeit vor jetzt (s)</translation>
        </message>
        <message>
            <source>time before the hold (s)</source>
            <translation>Zeit vor dem Anhalten (s)</translation>
        </message>
        <message>
            <source>Signals</source>
            <translation>Signale</translation>
        </message>
        <message>
            <source>Choose the output channels to plot</source>
            <translation>Die anzuzeigenden Ausgangskanäle wählen</translation>
        </message>
        <message>
            <source>Last {n} s</source>
            <translation>Letzte {n} s</translation>
        </message>
        <message>
            <source>How much time the plot shows</source>
            <translation>Wie viel Zeit die Kurve zeigt</translation>
        </message>
        <message>
            <source>Hold</source>
            <translation>Anhalten</translation>
        </message>
        <message>
            <source>Freeze the plot to read it; values keep being recorded</source>
            <translation>Kurve zum Ablesen anhalten; Werte werden weiter aufgezeichnet</translation>
        </message>
        <message>
            <source>Clear cursors</source>
            <translation>Cursor entfernen</translation>
        </message>
        <message>
            <source>Click the plot to set cursor A, right-click for cursor B; drag to move them</source>
            <translation>In die Kurve klicken setzt Cursor A, Rechtsklick Cursor B; ziehen verschiebt sie</translation>
        </message>
        <message>
            <source>Clear</source>
            <translation>Leeren</translation>
        </message>
        <message>
            <source>{device} output {index}</source>
            <translation>{device} Ausgang {index}</translation>
        </message>
        <message>
            <source>No output channels known yet</source>
            <translation>Noch keine Ausgangskanäle bekannt</translation>
        </message>
        <message>
            <source>{what} (on/off)</source>
            <translation>{what} (ein/aus)</translation>
        </message>
        <message>
            <source>unsigned</source>
            <translation>vorzeichenlos</translation>
        </message>
        <message>
            <source>signed</source>
            <translation>vorzeichenbehaftet</translation>
        </message>
        <message>
            <source>float</source>
            <translation>Gleitkomma</translation>
        </message>
    </context>
    <context>
        <name>FittingReport</name>
        <message>
            <source>PDCP fitting report</source>
            <translation>PDCP-Anpassungsbericht</translation>
        </message>
        <message>
            <source>Stored set-up written</source>
            <translation>Gespeicherte Einrichtung geschrieben</translation>
        </message>
        <message>
            <source>Current links stored as the set-up</source>
            <translation>Aktuelle Verbindungen als Einrichtung gespeichert</translation>
        </message>
        <message>
            <source>Autoconfigure turned on</source>
            <translation>Autokonfiguration eingeschaltet</translation>
        </message>
        <message>
            <source>Autoconfigure turned off</source>
            <translation>Autokonfiguration ausgeschaltet</translation>
        </message>
        <message>
            <source>Link added</source>
            <translation>Verbindung hinzugefügt</translation>
        </message>
        <message>
            <source>Link removed</source>
            <translation>Verbindung entfernt</translation>
        </message>
        <message>
            <source>Setting changed</source>
            <translation>Einstellung geändert</translation>
        </message>
        <message>
            <source>Changes written to the prosthesis</source>
            <translation>Änderungen in die Prothese geschrieben</translation>
        </message>
        <message>
            <source>applied</source>
            <translation>ausgeführt</translation>
        </message>
        <message>
            <source>rolled back</source>
            <translation>zurückgenommen</translation>
        </message>
        <message>
            <source>failed</source>
            <translation>fehlgeschlagen</translation>
        </message>
        <message>
            <source>Error</source>
            <translation>Fehler</translation>
        </message>
        <message>
            <source>Warning</source>
            <translation>Warnung</translation>
        </message>
        <message>
            <source>Info</source>
            <translation>Hinweis</translation>
        </message>
        <message>
            <source>Undone: {0}</source>
            <translation>Rückgängig gemacht: {0}</translation>
        </message>
        <message>
            <source>Done again: {0}</source>
            <translation>Wiederholt: {0}</translation>
        </message>
        <message>
            <source>{0} carried out</source>
            <translation>{0} ausgeführt</translation>
        </message>
        <message>
            <source>applied, verified</source>
            <translation>ausgeführt, geprüft</translation>
        </message>
        <message>
            <source>no change was made in this session</source>
            <translation>in dieser Sitzung wurde nichts geändert</translation>
        </message>
        <message>
            <source>every check passed</source>
            <translation>alle Prüfungen bestanden</translation>
        </message>
        <message>
            <source>a kind of signal the profile tree does not name</source>
            <translation>eine Signalart, die der Profilbaum nicht nennt</translation>
        </message>
        <message>
            <source>type {type}, profile {profile}</source>
            <translation>Typ {type}, Profil {profile}</translation>
        </message>
        <message>
            <source>not on the bus</source>
            <translation>nicht am Bus</translation>
        </message>
        <message>
            <source>VID {vid} PID {pid} serial {serial} channel {index} ({codes})</source>
            <translation>VID {vid} PID {pid} Seriennummer {serial} Kanal {index} ({codes})</translation>
        </message>
        <message>
            <source>(missing)</source>
            <translation>(fehlt)</translation>
        </message>
        <message>
            <source>{product} ({vendor})</source>
            <translation>{product} ({vendor})</translation>
        </message>
        <message>
            <source>not in the catalogue</source>
            <translation>nicht im Katalog</translation>
        </message>
        <message>
            <source>no devices</source>
            <translation>keine Geräte</translation>
        </message>
        <message>
            <source>Name</source>
            <translation>Name</translation>
        </message>
        <message>
            <source>Product</source>
            <translation>Produkt</translation>
        </message>
        <message>
            <source>Maker / product / serial no.</source>
            <translation>Hersteller / Produkt / Seriennr.</translation>
        </message>
        <message>
            <source>Firmware</source>
            <translation>Firmware</translation>
        </message>
        <message>
            <source>Hardware</source>
            <translation>Hardware</translation>
        </message>
        <message>
            <source>(to a missing device)</source>
            <translation>(zu einem fehlenden Gerät)</translation>
        </message>
        <message>
            <source>no links</source>
            <translation>keine Verbindungen</translation>
        </message>
        <message>
            <source>on</source>
            <translation>an</translation>
        </message>
        <message>
            <source>off</source>
            <translation>aus</translation>
        </message>
        <message>
            <source>Autoconfigure: {on} (the prosthesis may link parts that nothing drives on its own)</source>
            <translation>Autokonfiguration: {on} (die Prothese darf Teile, die nichts ansteuert, selbst verbinden)</translation>
        </message>
        <message>
            <source>Autoconfigure: {off} (the prosthesis repairs known links and finds replacements for missing parts, but links nothing new on its own)</source>
            <translation>Autokonfiguration: {off} (die Prothese repariert bekannte Verbindungen und findet Ersatz für fehlende Teile, verbindet aber nichts Neues von selbst)</translation>
        </message>
        <message>
            <source>Time (UTC)</source>
            <translation>Zeit (UTC)</translation>
        </message>
        <message>
            <source>Action</source>
            <translation>Aktion</translation>
        </message>
        <message>
            <source>Change</source>
            <translation>Änderung</translation>
        </message>
        <message>
            <source>Outcome</source>
            <translation>Ergebnis</translation>
        </message>
        <message>
            <source>By</source>
            <translation>Von</translation>
        </message>
        <message>
            <source>Changes made in this session ({n})</source>
            <translation>Änderungen in dieser Sitzung ({n})</translation>
        </message>
        <message>
            <source>Checks</source>
            <translation>Prüfungen</translation>
        </message>
        <message>
            <source>Finding</source>
            <translation>Befund</translation>
        </message>
        <message>
            <source>What</source>
            <translation>Was</translation>
        </message>
        <message>
            <source>Date: {0}</source>
            <translation>Datum: {0}</translation>
        </message>
        <message>
            <source>Patient:</source>
            <translation>Patient:</translation>
        </message>
        <message>
            <source>Prosthesis:</source>
            <translation>Prothese:</translation>
        </message>
        <message>
            <source>Prosthetist:</source>
            <translation>Orthopädietechniker:</translation>
        </message>
        <message>
            <source>Signature:</source>
            <translation>Unterschrift:</translation>
        </message>
        <message>
            <source>Devices ({n})</source>
            <translation>Geräte ({n})</translation>
        </message>
        <message>
            <source>Links ({n})</source>
            <translation>Verbindungen ({n})</translation>
        </message>
        <message>
            <source>Output</source>
            <translation>Ausgang</translation>
        </message>
        <message>
            <source>Input</source>
            <translation>Eingang</translation>
        </message>
        <message>
            <source>Stored set-up</source>
            <translation>Gespeicherte Einrichtung</translation>
        </message>
        <message>
            <source>Check number: {crc}{note}. A later reading of the prosthesis that shows the same number has the same links.</source>
            <translation>Prüfnummer: {crc}{note}. Eine spätere Auslesung der Prothese mit derselben Nummer hat dieselben Verbindungen.</translation>
        </message>
        <message>
            <source>Technical detail</source>
            <translation>Technische Einzelheiten</translation>
        </message>
        <message>
            <source>Check number: CRC-16/CCITT-FALSE of the stored configuration record. Links by identity (VID, PID, serial number, channel index) with the channels' type and profile codes:</source>
            <translation>Prüfnummer: CRC-16/CCITT-FALSE des gespeicherten Konfigurationsdatensatzes. Verbindungen nach Identität (VID, PID, Seriennummer, Kanalindex) mit den Typ- und Profilcodes der Kanäle:</translation>
        </message>
        <message>
            <source>Generated by PDCP Studio.</source>
            <translation>Erstellt mit PDCP Studio.</translation>
        </message>
        <message>
            <source>{path}: cannot write the PDF</source>
            <translation>{path}: Das PDF kann nicht geschrieben werden</translation>
        </message>
        <message>
            <source>{added}, {removed}</source>
            <translation>{added}, {removed}</translation>
        </message>
        <message numerus="yes">
            <source>%n link(s) added</source>
            <translation>
                <numerusform>%n Verbindung hinzugefügt</numerusform>
                <numerusform>%n Verbindungen hinzugefügt</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>%n removed</source>
            <translation>
                <numerusform>%n entfernt</numerusform>
                <numerusform>%n entfernt</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>%n parameter(s)</source>
            <translation>
                <numerusform>%n Parameter</numerusform>
                <numerusform>%n Parameter</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>(the %n link(s) above, as they would be stored)</source>
            <translation>
                <numerusform>(die %n Verbindung oben, wie sie gespeichert würde)</numerusform>
                <numerusform>(die %n Verbindungen oben, wie sie gespeichert würden)</numerusform>
            </translation>
        </message>
        <message>
            <source>(what the prosthesis stores: {links} in {setups})</source>
            <translation>(was die Prothese speichert: {links} in {setups})</translation>
        </message>
        <message numerus="yes">
            <source>%n link(s)</source>
            <translation>
                <numerusform>%n Verbindung</numerusform>
                <numerusform>%n Verbindungen</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>%n set-up(s)</source>
            <translation>
                <numerusform>%n Einrichtung</numerusform>
                <numerusform>%n Einrichtungen</numerusform>
            </translation>
        </message>
        <message>
            <source>Check number: CRC-16/CCITT-FALSE of the stored configuration record</source>
            <translation>Prüfnummer: CRC-16/CCITT-FALSE des gespeicherten Konfigurationsdatensatzes</translation>
        </message>
        <message>
            <source>Fitting history anchor in the prosthesis</source>
            <translation>Anker der Versorgungshistorie in der Prothese</translation>
        </message>
        <message>
            <source>entry {id}, hash {hash}</source>
            <translation>Eintrag {id}, Hash {hash}</translation>
        </message>
        <message>
            <source>VID {vid} PID {pid} serial {serial}</source>
            <translation>VID {vid} PID {pid} Seriennummer {serial}</translation>
        </message>
        <message>
            <source>Links by identity (VID, PID, serial number, channel index) with the channels&apos; type and profile codes:</source>
            <translation>Verbindungen nach Identität (VID, PID, Seriennummer, Kanalindex) mit den Typ- und Profilcodes der Kanäle:</translation>
        </message>
        <message>
            <source>No change was written in this session: the prosthesis starts up as it did before.</source>
            <translation>In dieser Sitzung wurde keine Änderung geschrieben: Die Prothese startet wie zuvor.</translation>
        </message>
        <message>
            <source>After entry {0}, the last change written:</source>
            <translation>Nach Eintrag {0}, der zuletzt geschriebenen Änderung:</translation>
        </message>
        <message>
            <source>Date:</source>
            <translation>Datum:</translation>
        </message>
        <message>
            <source>Patient: {0}</source>
            <translation>Patient: {0}</translation>
        </message>
        <message>
            <source>Page {page} of {pages}</source>
            <translation>Seite {page} von {pages}</translation>
        </message>
        <message>
            <source>At the next power-on: {0}</source>
            <translation>Beim nächsten Einschalten: {0}</translation>
        </message>
        <message>
            <source>next power-on adds</source>
            <translation>nächstes Einschalten fügt hinzu</translation>
        </message>
        <message>
            <source>next power-on removes</source>
            <translation>nächstes Einschalten entfernt</translation>
        </message>
        <message>
            <source>Parts by identity:</source>
            <translation>Teile nach Identität:</translation>
        </message>
        <message>
            <source>Next power-on</source>
            <translation>Nächstes Einschalten</translation>
        </message>
        <message>
            <source>stored configuration check number {before} → {after}</source>
            <translation>Prüfnummer der gespeicherten Konfiguration {before} → {after}</translation>
        </message>
        <message>
            <source>Entry {0}:</source>
            <translation>Eintrag {0}:</translation>
        </message>
        <message>
            <source>New fitting: links written</source>
            <translation>Neue Anpassung: Verbindungen geschrieben</translation>
        </message>
        <message>
            <source>New fitting: configuration stored</source>
            <translation>Neue Anpassung: Konfiguration gespeichert</translation>
        </message>
        <message>
            <source>Part replaced</source>
            <translation>Teil ersetzt</translation>
        </message>
        <message>
            <source>Configuration restored from a file</source>
            <translation>Konfiguration aus einer Datei wiederhergestellt</translation>
        </message>
        <message>
            <source>This entry was recorded before PDCP Studio predicted the next power-on, so the report cannot say what the prosthesis does at its next start-up.</source>
            <translation>Dieser Eintrag wurde aufgezeichnet, bevor PDCP Studio das nächste Einschalten vorhersagte; der Bericht kann daher nicht sagen, was die Prothese beim nächsten Start tut.</translation>
        </message>
        <message>
            <source>the prosthesis starts up with the links as they are now.</source>
            <translation>die Prothese startet mit den Verbindungen, wie sie jetzt sind.</translation>
        </message>
        <message>
            <source>Fitting history entry {0} restored</source>
            <translation>Eintrag {0} der Anpassungshistorie wiederhergestellt</translation>
        </message>
        <message>
            <source>{old} replaced by {new}</source>
            <translation>{old} ersetzt durch {new}</translation>
        </message>
        <message>
            <source>Autoconfigure: not known (the prosthesis was not connected)</source>
            <translation>Autokonfiguration: unbekannt (die Prothese war nicht verbunden)</translation>
        </message>
    </context>
    <context>
        <name>StartView</name>
        <message>
            <source>New fitting</source>
            <translation>Neue Versorgung</translation>
        </message>
        <message>
            <source>Connect to a prosthesis, check it, link its parts and store the result, step by step.</source>
            <translation>Mit einer Prothese verbinden, sie prüfen, ihre Teile verbinden und das Ergebnis speichern, Schritt für Schritt.</translation>
        </message>
        <message>
            <source>Replace a part</source>
            <translation>Ein Teil ersetzen</translation>
        </message>
        <message>
            <source>Swap a part and link the new one in its place, with how alike it is said in words.</source>
            <translation>Ein Teil tauschen und das neue an seiner Stelle verbinden; wie ähnlich es ist, wird in Worten gesagt.</translation>
        </message>
        <message>
            <source>Restore a configuration</source>
            <translation>Eine Konfiguration wiederherstellen</translation>
        </message>
        <message>
            <source>Put a configuration file or an earlier fitting back on the prosthesis.</source>
            <translation>Eine Konfigurationsdatei oder eine frühere Versorgung wieder auf die Prothese bringen.</translation>
        </message>
        <message>
            <source>PDCP Studio</source>
            <translation>PDCP Studio</translation>
        </message>
        <message>
            <source>See and set up the parts of a powered prosthesis. Choose what you would like to do:</source>
            <translation>Die Teile einer elektrisch angetriebenen Prothese sehen und einrichten. Wählen Sie, was Sie tun möchten:</translation>
        </message>
        <message>
            <source>Guided tasks</source>
            <translation>Geführte Aufgaben</translation>
        </message>
        <message>
            <source>Work directly</source>
            <translation>Direkt arbeiten</translation>
        </message>
        <message>
            <source>Connect to a prosthesis…</source>
            <translation>Mit einer Prothese verbinden…</translation>
        </message>
        <message>
            <source>Through a CAN adapter or the arbitrator's cable, to see it live.</source>
            <translation>Über einen CAN-Adapter oder das serielle Kabel des Arbiters, um sie live zu sehen.</translation>
        </message>
        <message>
            <source>Open a file…</source>
            <translation>Eine Datei öffnen…</translation>
        </message>
        <message>
            <source>A saved prosthesis or a stored configuration, to look at or prepare.</source>
            <translation>Eine gespeicherte Prothese oder eine gespeicherte Konfiguration, zum Ansehen oder Vorbereiten.</translation>
        </message>
        <message>
            <source>Try the simulated prosthesis</source>
            <translation>Die simulierte Prothese ausprobieren</translation>
        </message>
        <message>
            <source>A transradial prosthesis with a spare hand, to practise on without a patient.</source>
            <translation>Eine transradiale Prothese mit einer Ersatzhand, zum Üben ohne Patienten.</translation>
        </message>
        <message>
            <source>Recent files</source>
            <translation>Zuletzt geöffnete Dateien</translation>
        </message>
        <message>
            <source>No file opened yet. Files you open or save appear here.</source>
            <translation>Noch keine Datei geöffnet. Dateien, die Sie öffnen oder speichern, erscheinen hier.</translation>
        </message>
    </context>
    <context>
        <name>PartNames</name>
        <message>
            <source>{name} (serial {serial})</source>
            <translation>{name} (Seriennummer {serial})</translation>
        </message>
        <message>
            <source>VID {vid} · PID {pid} · serial {serial}</source>
            <translation>VID {vid} · PID {pid} · Seriennummer {serial}</translation>
        </message>
    </context>
    <context>
        <name>SimPanel</name>
        <message>
            <source>Product</source>
            <translation>Produkt</translation>
        </message>
        <message>
            <source>unknown</source>
            <translation>unbekannt</translation>
        </message>
    </context>
    <context>
        <name>SessionBridge</name>
        <message>
            <source>Plugging in {device}</source>
            <translation>{device} wird eingesteckt</translation>
        </message>
        <message>
            <source>Plugged in {device}</source>
            <translation>{device} eingesteckt</translation>
        </message>
        <message>
            <source>Unplugging {device}</source>
            <translation>{device} wird ausgesteckt</translation>
        </message>
        <message>
            <source>Unplugged {device}</source>
            <translation>{device} ausgesteckt</translation>
        </message>
        <message>
            <source>Replacing {old} by {new}</source>
            <translation>{old} wird durch {new} ersetzt</translation>
        </message>
        <message>
            <source>Replaced {old} by {new}</source>
            <translation>{old} durch {new} ersetzt</translation>
        </message>
        <message>
            <source>Restarting the arbitrator, keeping its memory</source>
            <translation>Der Arbiter wird neu gestartet, sein Speicher bleibt erhalten</translation>
        </message>
        <message>
            <source>Restarting the arbitrator, erasing its memory</source>
            <translation>Der Arbiter wird neu gestartet, sein Speicher wird gelöscht</translation>
        </message>
        <message>
            <source>The arbitrator restarted; its stored configuration was kept</source>
            <translation>Der Arbiter wurde neu gestartet; seine gespeicherte Konfiguration blieb erhalten</translation>
        </message>
        <message>
            <source>The arbitrator restarted with its memory erased</source>
            <translation>Der Arbiter wurde mit gelöschtem Speicher neu gestartet</translation>
        </message>
        <message>
            <source>Script {name} finished</source>
            <translation>Skript {name} beendet</translation>
        </message>
        <message>
            <source>Script {name}</source>
            <translation>Skript {name}</translation>
        </message>
    </context>
    <context>
        <name>SimPanel</name>
        <message>
            <source>Stored the current links in the arbitrator's memory</source>
            <translation>Die aktuellen Verbindungen wurden im Speicher des Arbiters abgelegt</translation>
        </message>
    </context>
    <context>
        <name>BusScene</name>
        <message>
            <source>Missing from the bus</source>
            <translation>Fehlt am Bus</translation>
        </message>
        <message>
            <source>node ID {0}</source>
            <translation>Knoten-ID {0}</translation>
        </message>
        <message>
            <source>Input {n}</source>
            <translation>Eingang {n}</translation>
        </message>
        <message>
            <source>Output {n}</source>
            <translation>Ausgang {n}</translation>
        </message>
        <message>
            <source>Fed by {0}</source>
            <translation>Gespeist von {0}</translation>
        </message>
        <message>
            <source>Nothing feeds it</source>
            <translation>Nichts speist ihn</translation>
        </message>
        <message>
            <source>Feeds {0}</source>
            <translation>Speist {0}</translation>
        </message>
        <message>
            <source>Feeds nothing</source>
            <translation>Speist nichts</translation>
        </message>
        <message>
            <source>profile {profile} · signal type {type}: {description}</source>
            <translation>Profil {profile} · Signaltyp {type}: {description}</translation>
        </message>
        <message>
            <source>drives the part with profile {0}</source>
            <translation>treibt das Teil mit Profil {0}</translation>
        </message>
    </context>
    <context>
        <name>PlanWords</name>
        <message>
            <source> (missing)</source>
            <translation> (fehlt)</translation>
        </message>
        <message>
            <source>The plan adds this link:</source>
            <translation>Der Plan fügt diese Verbindung hinzu:</translation>
        </message>
        <message>
            <source>The plan removes this link:</source>
            <translation>Der Plan entfernt diese Verbindung:</translation>
        </message>
        <message>
            <source>Why: {0}</source>
            <translation>Warum: {0}</translation>
        </message>
        <message>
            <source>How similar: {0}</source>
            <translation>Wie ähnlich: {0}</translation>
        </message>
        <message numerus="yes">
            <source>similar signal (%n level(s) alike)</source>
            <translation>
                <numerusform>ähnliches Signal (%n Ebene gleich)</numerusform>
                <numerusform>ähnliches Signal (%n Ebenen gleich)</numerusform>
            </translation>
        </message>
    </context>
    <context>
        <name>Inspector</name>
        <message>
            <source>Details for engineers</source>
            <translation>Details für Techniker</translation>
        </message>
        <message>
            <source>{product} by {vendor}</source>
            <translation>{product} von {vendor}</translation>
        </message>
        <message>
            <source>a product no device catalogue knows</source>
            <translation>ein Produkt, das kein Gerätekatalog kennt</translation>
        </message>
        <message>
            <source>missing from the bus</source>
            <translation>fehlt am Bus</translation>
        </message>
        <message>
            <source>Name (PDCP Studio)</source>
            <translation>Name (PDCP Studio)</translation>
        </message>
        <message>
            <source>Product</source>
            <translation>Produkt</translation>
        </message>
        <message>
            <source>not in the catalogue</source>
            <translation>nicht im Katalog</translation>
        </message>
        <message>
            <source>Maker</source>
            <translation>Hersteller</translation>
        </message>
        <message>
            <source>Kind</source>
            <translation>Art</translation>
        </message>
        <message>
            <source>Identity</source>
            <translation>Kennung</translation>
        </message>
        <message>
            <source>VID/PID/serial</source>
            <translation>VID/PID/Seriennummer</translation>
        </message>
        <message>
            <source>Input {n}: {what}</source>
            <translation>Eingang {n}: {what}</translation>
        </message>
        <message>
            <source>Output {n}: {what}</source>
            <translation>Ausgang {n}: {what}</translation>
        </message>
        <message>
            <source>Profile code</source>
            <translation>Profilcode</translation>
        </message>
        <message>
            <source>parameter 1, bytes 2–3</source>
            <translation>Parameter 1, Bytes 2–3</translation>
        </message>
        <message>
            <source>Control mode</source>
            <translation>Steuerungsart</translation>
        </message>
        <message>
            <source>Channel type</source>
            <translation>Kanaltyp</translation>
        </message>
        <message>
            <source>code {code} (suggested ×{hint})</source>
            <translation>Code {code} (vorgeschlagen ×{hint})</translation>
        </message>
        <message>
            <source>The prescaler's raw 3-bit code; the factor is the thesis's suggestion only and nothing is computed from it</source>
            <translation>Der rohe 3-Bit-Code des Vorteilers; der Faktor ist nur der Vorschlag der Arbeit, nichts wird daraus berechnet</translation>
        </message>
        <message>
            <source>Fed by {0}</source>
            <translation>Gespeist von {0}</translation>
        </message>
        <message>
            <source>Nothing feeds it (not linked)</source>
            <translation>Nichts speist ihn (nicht verbunden)</translation>
        </message>
        <message>
            <source>Feeds {0}</source>
            <translation>Speist {0}</translation>
        </message>
        <message>
            <source>Feeds nothing</source>
            <translation>Speist nichts</translation>
        </message>
    </context>
    <context>
        <name>LivePlot</name>
        <message>
            <source>{quantity} (raw)</source>
            <translation>{quantity} (roh)</translation>
        </message>
        <message>
            <source>suggested {factor}</source>
            <translation>vorgeschlagen {factor}</translation>
        </message>
    </context>
    <context>
        <name>Wizards</name>
        <message numerus="yes">
            <source>%n link(s) could not be made (the engineer's detail says why).</source>
            <translation>
                <numerusform>%n Verbindung konnte nicht hergestellt werden (die Details für Techniker sagen, warum).</numerusform>
                <numerusform>%n Verbindungen konnten nicht hergestellt werden (die Details für Techniker sagen, warum).</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>%n part(s) found on the bus</source>
            <translation>
                <numerusform>%n Teil am Bus gefunden</numerusform>
                <numerusform>%n Teile am Bus gefunden</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>%n link(s) between them:</source>
            <translation>
                <numerusform>%n Verbindung zwischen ihnen:</numerusform>
                <numerusform>%n Verbindungen zwischen ihnen:</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>%n thing(s) to look at. The next step proposes links that fix what can be fixed automatically:</source>
            <translation>
                <numerusform>%n Punkt zu prüfen. Der nächste Schritt schlägt Verbindungen vor, die automatisch behebbare Probleme beheben:</numerusform>
                <numerusform>%n Punkte zu prüfen. Der nächste Schritt schlägt Verbindungen vor, die automatisch behebbare Probleme beheben:</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>On the prosthesis as planned: %n link(s).</source>
            <translation>
                <numerusform>Wie geplant auf der Prothese: %n Verbindung.</numerusform>
                <numerusform>Wie geplant auf der Prothese: %n Verbindungen.</numerusform>
            </translation>
        </message>
        <message>
            <source>{0}: written and verified ({1}, {2})</source>
            <translation>{0}: geschrieben und geprüft ({1}, {2})</translation>
        </message>
        <message numerus="yes">
            <source>%n link(s) on the prosthesis</source>
            <translation>
                <numerusform>%n Verbindung auf der Prothese</numerusform>
                <numerusform>%n Verbindungen auf der Prothese</numerusform>
            </translation>
        </message>
        <message>
            <source>{0} is not on the bus; {1}</source>
            <translation>{0} ist nicht am Bus; {1}</translation>
        </message>
        <message numerus="yes">
            <source>%n link(s) led to it.</source>
            <translation>
                <numerusform>%n Verbindung führte zu ihm.</numerusform>
                <numerusform>%n Verbindungen führten zu ihm.</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>The prosthesis made %n link(s) of these on its own when the part was plugged in; the write makes them part of the fitting.</source>
            <translation>
                <numerusform>Die Prothese hat %n dieser Verbindungen beim Einstecken des Teils selbst hergestellt; das Schreiben macht sie zum Teil der Versorgung.</numerusform>
                <numerusform>Die Prothese hat %n dieser Verbindungen beim Einstecken des Teils selbst hergestellt; das Schreiben macht sie zum Teil der Versorgung.</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>Already on the prosthesis and kept as they are: %n link(s).</source>
            <translation>
                <numerusform>Schon auf der Prothese und unverändert beibehalten: %n Verbindung.</numerusform>
                <numerusform>Schon auf der Prothese und unverändert beibehalten: %n Verbindungen.</numerusform>
            </translation>
        </message>
        <message>
            <source>Entry {0} — {1} — {2} ({3})</source>
            <translation>Eintrag {0} — {1} — {2} ({3})</translation>
        </message>
        <message numerus="yes">
            <source>%n link(s)</source>
            <translation>
                <numerusform>%n Verbindung</numerusform>
                <numerusform>%n Verbindungen</numerusform>
            </translation>
        </message>
        <message>
            <source>{0}: {1}</source>
            <translation>{0}: {1}</translation>
        </message>
        <message numerus="yes">
            <source>%n stored link(s).</source>
            <translation>
                <numerusform>%n gespeicherte Verbindung.</numerusform>
                <numerusform>%n gespeicherte Verbindungen.</numerusform>
            </translation>
        </message>
        <message>
            <source>On this simulated prosthesis: in the Simulator panel choose the spare hand and press Plug in.</source>
            <translation>An dieser simulierten Prothese: Wählen Sie im Simulator-Bereich die Ersatzhand und drücken Sie „Anstecken“.</translation>
        </message>
        <message>
            <source>To try a swap on this simulated prosthesis: in the Simulator panel choose the hand and press Unplug. This page follows the bus and shows the missing part.</source>
            <translation>Um an dieser simulierten Prothese einen Tausch zu üben: Wählen Sie im Simulator-Bereich die Hand und drücken Sie „Abziehen“. Diese Seite folgt dem Bus und zeigt das fehlende Teil.</translation>
        </message>
        <message>
            <source>Seen on the bus: {0} (new).</source>
            <translation>Am Bus erkannt: {0} (neu).</translation>
        </message>
    </context>
    <context>
        <name>Inspector</name>
        <message>
            <source>A device catalogue file was skipped, so the parts it describes are not named from it: {0}</source>
            <translation>Eine Gerätekatalog-Datei wurde übersprungen, daher werden die Teile, die sie beschreibt, nicht danach benannt: {0}</translation>
        </message>
        <message>
            <source>(none)</source>
            <translation>(keins)</translation>
        </message>
        <message>
            <source>Not in the profile tree</source>
            <translation>Nicht im Profilbaum</translation>
        </message>
        <message>
            <source>Profile code {code}</source>
            <translation>Profilcode {code}</translation>
        </message>
        <message>
            <source>{name}: profile code {code} (parameter 1, bytes 2–3).
Choose a profile of the named tree or type one in hex.</source>
            <translation>{name}: Profilcode {code} (Parameter 1, Bytes 2–3).
Wählen Sie ein Profil aus dem Namensbaum oder geben Sie eines hexadezimal ein.</translation>
        </message>
    </context>
    <context>
        <name>OpenFile</name>
        <message numerus="yes">
            <source>%n link(s) left out: </source>
            <translation>
                <numerusform>%n Verbindung ausgelassen: </numerusform>
                <numerusform>%n Verbindungen ausgelassen: </numerusform>
            </translation>
        </message>
    </context>
    <context>
        <name>Names</name>
        <message>
            <source>{name} (serial {serial})</source>
            <translation>{name} (Seriennummer {serial})</translation>
        </message>
        <message>
            <source>{part}, {channel}</source>
            <translation>{part}, {channel}</translation>
        </message>
        <message>
            <source>channel {n}</source>
            <translation>Kanal {n}</translation>
        </message>
        <message>
            <source>{name} ({channel})</source>
            <translation>{name} ({channel})</translation>
        </message>
        <message>
            <source>{output} → {input}</source>
            <translation>{output} → {input}</translation>
        </message>
        <message>
            <source>VID {vid} · PID {pid} · serial {serial}</source>
            <translation>VID {vid} · PID {pid} · Seriennummer {serial}</translation>
        </message>
    </context>
    <context>
        <name>TransactionOutcome</name>
        <message>
            <source>{what}: failed while {step}</source>
            <translation>{what}: {step} fehlgeschlagen</translation>
        </message>
        <message>
            <source>{what}: stopped while {step}; what was written is undone</source>
            <translation>{what}: {step} abgebrochen; was geschrieben war, ist rückgängig gemacht</translation>
        </message>
        <message>
            <source>{what}: not confirmed, nothing written</source>
            <translation>{what}: nicht bestätigt, nichts geschrieben</translation>
        </message>
        <message>
            <source>{what}: nothing to change on the prosthesis</source>
            <translation>{what}: an der Prothese ist nichts zu ändern</translation>
        </message>
        <message numerus="yes">
            <source>%n part(s) held still while writing</source>
            <translation>
                <numerusform>%n Teil während des Schreibens stillgehalten</numerusform>
                <numerusform>%n Teile während des Schreibens stillgehalten</numerusform>
            </translation>
        </message>
        <message numerus="yes">
            <source>%n link(s) on the prosthesis</source>
            <translation>
                <numerusform>%n Verbindung an der Prothese</numerusform>
                <numerusform>%n Verbindungen an der Prothese</numerusform>
            </translation>
        </message>
        <message>
            <source>{what}: written and verified — {links}</source>
            <translation>{what}: geschrieben und geprüft — {links}</translation>
        </message>
        <message>
            <source>recording in the fitting history</source>
            <translation>beim Eintragen ins Versorgungsprotokoll</translation>
        </message>
        <message>
            <source>releasing the parts</source>
            <translation>beim Freigeben der Teile</translation>
        </message>
        <message>
            <source>putting back</source>
            <translation>beim Zurücksetzen</translation>
        </message>
        <message>
            <source>reading back</source>
            <translation>beim Zurücklesen</translation>
        </message>
        <message>
            <source>writing</source>
            <translation>beim Schreiben</translation>
        </message>
        <message>
            <source>holding the parts still</source>
            <translation>beim Stillhalten der Teile</translation>
        </message>
        <message>
            <source>asking for confirmation</source>
            <translation>bei der Bestätigung</translation>
        </message>
        <message>
            <source>previewing</source>
            <translation>bei der Vorschau</translation>
        </message>
    </context>
    <context>
        <name>SignIn</name>
        <message>
            <source>Fitting history: not signed in</source>
            <translation>Anpassungshistorie: nicht angemeldet</translation>
        </message>
        <message>
            <source>Fitting history: this computer</source>
            <translation>Anpassungshistorie: dieser Computer</translation>
        </message>
        <message>
            <source>Fitting history: signed in as {0}, read only</source>
            <translation>Anpassungshistorie: angemeldet als {0}, nur lesen</translation>
        </message>
        <message>
            <source>Fitting history: signed in as {0}</source>
            <translation>Anpassungshistorie: angemeldet als {0}</translation>
        </message>
        <message>
            <source>Sign in to the fitting history</source>
            <translation>An der Anpassungshistorie anmelden</translation>
        </message>
        <message>
            <source>The clinic's fitting history at {0} asks for your password.
{1}
Password (kept only while PDCP Studio runs):</source>
            <translation>Die Anpassungshistorie der Klinik unter {0} verlangt Ihr Passwort.
{1}
Passwort (nur aufbewahrt, solange PDCP Studio läuft):</translation>
        </message>
    </context>
</TS>
