#pragma once
// A diagram whose names hold what the HTML parser reads inside a <script>:
// "</script>" would end it, "<!--" with "<script>" would hide the rest of
// the page; '&', U+2028 and U+2029 for good measure. Its files are named
// d.csv and d.html (the diagram's name holds a '/').

namespace mechflow::testing {

// The moving body's label in the page (mechanism.body).
inline constexpr const char* kHostileBodyLabel = "m.<!--<script>";

inline constexpr const char* kHostileNamesDiagram =
    "<diagram name='&lt;!--&lt;script&gt; &lt;/script&gt; diagram'>\n"
    "<mechanism name='m'>\n"
    "  <body name='&lt;!--&lt;script&gt;' mass='1' inertia='1 1 1'/>\n"
    "  <joint name='j' type='generalized' body1='Base0' body2='&lt;!--&lt;script&gt;'>"
    "<et type='tt' axis='0 0 1' value='t'/></joint>\n"
    "  <shape type='box' body='&lt;!--&lt;script&gt;' size='0.2 0.2 0.2' color='#cc2222'"
    " name='&lt;/script&gt; &lt;!-- &amp; &#x2028; &#x2029;'/>\n"
    "  <sensor name='z' kind='position' body='&lt;!--&lt;script&gt;' component='z'/>\n"
    "</mechanism>\n"
    "<solver t_end='1'/>\n"
    "<output interval='0.01' csv='d.csv' animation='d.html'>"
    "<log signal='m.z' label='z &lt;!--&lt;script&gt;'/></output>\n"
    "</diagram>\n";

}  // namespace mechflow::testing
