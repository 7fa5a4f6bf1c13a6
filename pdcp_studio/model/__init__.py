"""Domain model: devices, channels, types, profiles, profile trees, links, systems. Pure."""

from pdcp_studio.model.channel_type import ChannelType, ControlMode, DataType
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
)
from pdcp_studio.model.profile_tree import ProfileNode, ProfileTree
from pdcp_studio.model.refs import ChannelRef, DeviceKey, Direction
from pdcp_studio.model.system import NO_SOURCE, Channel, Device, Link, SourceInfo, System

__all__ = [
    "NO_SOURCE",
    "Channel",
    "ChannelRef",
    "ChannelType",
    "ConfigCollection",
    "ControlMode",
    "DataType",
    "Device",
    "DeviceKey",
    "Direction",
    "Link",
    "ProfileNode",
    "ProfileTree",
    "SourceInfo",
    "StoredChannel",
    "StoredConfiguration",
    "StoredLink",
    "System",
]
