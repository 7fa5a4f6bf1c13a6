"""The bus graph: device cards, ports and links in a QGraphicsScene that follows a Document."""
