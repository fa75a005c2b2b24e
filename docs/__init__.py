"""The user guide and its pictures, shipped as package data of ``mrm.docs`` (see ``mrm.resources``)."""
