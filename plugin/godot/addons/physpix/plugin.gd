tool
extends EditorPlugin
# The nodes are class_name scripts, so the editor lists them once the project's scripts are scanned;
# the plugin itself adds nothing.
