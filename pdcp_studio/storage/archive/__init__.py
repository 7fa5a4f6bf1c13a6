"""The fitting history's archive: one interface (:mod:`.base`), two engines (:mod:`.sqlite`,
:mod:`.postgres`), the pure hash chain both share (:mod:`.chain`), chosen by URL
(:mod:`.open`); moving entries between archives (:mod:`.transfer`)."""

from pdcp_studio.storage.archive.base import (
    Archive,
    Entry,
    EntryFilter,
    HistoryError,
    NotAllowedError,
)
from pdcp_studio.storage.archive.chain import VerifyReport
from pdcp_studio.storage.archive.open import archive_url, describe, open_archive, open_existing

__all__ = ["Archive", "Entry", "EntryFilter", "HistoryError", "NotAllowedError",
           "VerifyReport", "archive_url", "describe", "open_archive", "open_existing"]
